//! The order in which the legs' loads are summed (eqs. 66-68): one fixed by the gear's geometry,
//! not by the legs' numbering. A sum rounded term by term depends on the order of its terms, so
//! summed in index order a landing and the same landing with its legs renumbered, or its mirror
//! image, part at the rounding level, and a footpad with inertia amplifies that
//! (docs/errata.md, "Decisions at rounding level").
//!
//! The legs are ordered by their primary trunnion B2 in body axes, by (y, z, |x|): renumbering
//! the legs does not change that order, and neither does the mirror x → −x. Mirror-twin legs
//! (the same y, z and |x|) are added to each other first, which is the same in either order, and
//! their sum then joins the total. So renumbered and mirrored landings sum their loads in the
//! same order, bit for bit, at the cost of plain additions.

use nalgebra::Vector3;
use std::cmp::Ordering;
use std::ops::Add;
use touchdown_scenario::model::Leg;

/// The legs' summation order: groups of one leg, or of two mirror-twin legs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SumOrder {
    /// Each group's legs (the same index twice for a group of one), in summation order.
    groups: Vec<[usize; 2]>,
}

impl SumOrder {
    /// The order for `legs`.
    pub(crate) fn new(legs: &[Leg]) -> SumOrder {
        let key = |i: usize| {
            let b = &legs[i].b2;
            [b.y, b.z, b.x.abs()]
        };
        let cmp = |a: usize, b: usize| {
            let (ka, kb) = (key(a), key(b));
            (ka.iter().zip(&kb))
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| *o != Ordering::Equal)
                .unwrap_or(Ordering::Equal)
        };
        let mut order: Vec<usize> = (0..legs.len()).collect();
        // A stable sort: legs with the same key keep their index order, which only legs
        // sharing one trunnion (more than two to a key) can see.
        order.sort_by(|&a, &b| cmp(a, b));
        let mut groups = Vec::with_capacity(order.len());
        let mut k = 0;
        while k < order.len() {
            let i = order[k];
            let twin = order.get(k + 1).filter(|&&j| {
                cmp(i, j) == Ordering::Equal
                    && order
                        .get(k + 2)
                        .is_none_or(|&l| cmp(j, l) != Ordering::Equal)
            });
            match twin {
                Some(&j) => {
                    groups.push([i, j]);
                    k += 2;
                }
                None => {
                    groups.push([i, i]);
                    k += 1;
                }
            }
        }
        SumOrder { groups }
    }

    /// The sum of `terms` (one per leg) in this order: [`SumOrder::sum_by`]'s loop written out,
    /// which the loads' evaluation calls twice a force evaluation (through the closure it
    /// cost 0.5 % more instructions of a campaign, docs/performance.md, "T_BI written out, the
    /// legs' sums in place").
    #[inline]
    pub(crate) fn sum(&self, terms: &[Vector3<f64>]) -> Vector3<f64> {
        let mut total = Vector3::zeros();
        for &[i, j] in &self.groups {
            total += if i == j {
                terms[i]
            } else {
                terms[i] + terms[j]
            };
        }
        total
    }

    /// The sum from `zero` of each leg's `term` (by index) in this order.
    #[inline]
    pub(crate) fn sum_by<T: Copy + Add<Output = T>>(
        &self,
        zero: T,
        term: impl Fn(usize) -> T,
    ) -> T {
        self.fold_by(zero, term, |a, b| a + b)
    }

    /// [`SumOrder::sum_by`] with the addition `add` (for terms that are not one number or
    /// vector: pairs of sums added in one pass).
    #[inline]
    pub(crate) fn fold_by<T: Copy>(
        &self,
        zero: T,
        term: impl Fn(usize) -> T,
        add: impl Fn(T, T) -> T,
    ) -> T {
        let mut total = zero;
        for &[i, j] in &self.groups {
            total = add(
                total,
                if i == j {
                    term(i)
                } else {
                    add(term(i), term(j))
                },
            );
        }
        total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leg(x: f64, y: f64) -> Leg {
        let b2 = Vector3::new(x, y, 1.0);
        Leg {
            b2,
            b3: b2,
            b4: b2,
            bp: b2,
            l21: 1.0,
            l2p: 1.0,
            l31: 1.0,
            l41: 1.0,
        }
    }

    /// Terms whose sum depends on the order of a naive sum.
    fn terms() -> Vec<Vector3<f64>> {
        vec![
            Vector3::new(1e16, 0.1, 3.0),
            Vector3::new(1.0, 0.2, -1e-17),
            Vector3::new(-1e16, 0.3, 7.0),
            Vector3::new(0.7, 1e-3, 1e20),
        ]
    }

    /// Three legs of a square and a fourth at (x, y).
    fn legs(x: f64, y: f64) -> [Leg; 4] {
        [leg(1.0, 1.0), leg(-1.0, 1.0), leg(-1.0, -1.0), leg(x, y)]
    }

    #[test]
    fn renumbered_legs_sum_alike() {
        let legs = legs(1.0, -1.0);
        let t = terms();
        let reference = SumOrder::new(&legs).sum(&t);
        for shift in 1..4 {
            let map: Vec<usize> = (0..4).map(|k| (k + shift) % 4).collect();
            let renumbered: Vec<Leg> = map.iter().map(|&i| legs[i]).collect();
            let moved: Vec<_> = map.iter().map(|&i| t[i]).collect();
            assert_eq!(SumOrder::new(&renumbered).sum(&moved), reference);
        }
    }

    #[test]
    fn a_mirror_image_sums_to_the_mirrored_sum() {
        let legs = legs(0.5, -2.0);
        let t = terms();
        let mirror = |v: &Vector3<f64>| Vector3::new(-v.x, v.y, v.z);
        let image: Vec<Leg> = legs.iter().map(|l| leg(-l.b2.x, l.b2.y)).collect();
        let mirrored: Vec<_> = t.iter().map(mirror).collect();
        assert_eq!(
            SumOrder::new(&image).sum(&mirrored),
            mirror(&SumOrder::new(&legs).sum(&t))
        );
        // Twins (±x) are summed as a pair, singles alone.
        assert_eq!(SumOrder::new(&legs).groups.len(), 3);
    }

    #[test]
    fn the_order_matters_to_a_naive_sum() {
        // What the order above protects against: the same terms in another order.
        let t = terms();
        let forward = t.iter().fold(Vector3::zeros(), |a, b| a + b);
        let backward = t.iter().rev().fold(Vector3::zeros(), |a, b| a + b);
        assert_ne!(forward, backward);
    }
}
