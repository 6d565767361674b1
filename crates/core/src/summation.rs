//! The order in which the legs' loads are summed (eqs. 66-68): one fixed by the gear's geometry,
//! not by the legs' numbering. A sum rounded term by term depends on the order of its terms, so
//! summed in index order a landing and the same landing with its legs renumbered, or its mirror
//! image, part at the rounding level, and a footpad with inertia amplifies that
//! (docs/errata.md, "Decisions at rounding level").
//!
//! The legs are ordered by their primary trunnion B2 in body axes: by ring (height z, then
//! distance from the centre line, as x² + y²), then by (y, |x|). None of these changes when the
//! legs are renumbered, and the ring does not change under any turn or mirror about the centre
//! line. A ring of four legs in two diametral pairs (the report's gear) is summed as the sum of
//! its two pairs' sums, which any turn or mirror that maps the gear onto itself leaves the same
//! bit for bit: it maps pairs onto pairs, and an addition of two terms is the same in either
//! order. So the 2-2 landing, whose plane of symmetry is a diagonal of the body axes, sums its
//! loads as its mirror image does, as the 1-2-1 landing does. Elsewhere mirror-twin legs (the same
//! y, z and |x|) are added to each other first and their sum then joins the total, which the
//! mirror x → −x leaves the same. All at the cost of plain additions.

use nalgebra::Vector3;
use std::cmp::Ordering;
use std::ops::Add;
use touchdown_scenario::model::Leg;

/// One group of legs summed on its own before it joins the total.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Group {
    /// A leg alone.
    One(usize),
    /// Two mirror-twin legs, or a ring of two.
    Two([usize; 2]),
    /// A ring of four legs in two diametral pairs, each pair's legs first: (a + c) + (b + d).
    Four([usize; 4]),
}

/// The legs' summation order: groups of one leg, of two mirror-twin legs, or of a ring of four.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SumOrder {
    /// The groups, in summation order.
    groups: Vec<Group>,
}

/// Lexicographic order of two keys of floats.
fn lexicographic(a: &[f64], b: &[f64]) -> Ordering {
    (a.iter().zip(b))
        .map(|(x, y)| x.total_cmp(y))
        .find(|o| *o != Ordering::Equal)
        .unwrap_or(Ordering::Equal)
}

impl SumOrder {
    /// The order for `legs`.
    pub(crate) fn new(legs: &[Leg]) -> SumOrder {
        let b2 = |i: usize| legs[i].b2;
        let ring = |i: usize| {
            let b = b2(i);
            [b.z, b.x * b.x + b.y * b.y]
        };
        let key = |i: usize| {
            let b = b2(i);
            let [z, r2] = ring(i);
            [z, r2, b.y, b.x.abs()]
        };
        let mut order: Vec<usize> = (0..legs.len()).collect();
        // A stable sort: legs with the same key keep their index order, which only legs
        // sharing one trunnion (more than two to a key) can see.
        order.sort_by(|&a, &b| lexicographic(&key(a), &key(b)));
        let diametral = |i: usize, j: usize| b2(i).x == -b2(j).x && b2(i).y == -b2(j).y;
        let mut groups = Vec::with_capacity(order.len());
        let mut k = 0;
        while k < order.len() {
            let same_ring = order[k..]
                .iter()
                .take_while(|&&j| lexicographic(&ring(order[k]), &ring(j)).is_eq())
                .count();
            let r = &order[k..k + same_ring];
            if let [a, b, c, d] = *r {
                // the partner of a among the other three, then whether the last two pair up
                let quad = [[a, b, c, d], [a, c, b, d], [a, d, b, c]]
                    .into_iter()
                    .find(|q| diametral(q[0], q[1]) && diametral(q[2], q[3]));
                if let Some([a, c, b, d]) = quad {
                    groups.push(Group::Four([a, c, b, d]));
                    k += 4;
                    continue;
                }
            }
            let end = k + same_ring;
            while k < end {
                let i = order[k];
                let twin = order[..end].get(k + 1).filter(|&&j| {
                    key(i) == key(j) && order[..end].get(k + 2).is_none_or(|&l| key(j) != key(l))
                });
                match twin {
                    Some(&j) => {
                        groups.push(Group::Two([i, j]));
                        k += 2;
                    }
                    None => {
                        groups.push(Group::One(i));
                        k += 1;
                    }
                }
            }
        }
        SumOrder { groups }
    }

    /// The sums of the legs' forces and of their moments (one of each per leg) in this order:
    /// [`SumOrder::sum_by`]'s loop written out for the two in one pass, which the loads'
    /// evaluation calls once a force evaluation (through the closure it cost 0.5 % more
    /// instructions of a campaign, docs/performance.md, "T_BI written out, the legs' sums in
    /// place"; one pass for the two, "The legs' forces and moments summed in one pass").
    #[inline]
    pub(crate) fn sum_loads(
        &self,
        forces: &[Vector3<f64>],
        moments: &[Vector3<f64>],
    ) -> (Vector3<f64>, Vector3<f64>) {
        let (mut force, mut moment) = (Vector3::zeros(), Vector3::zeros());
        for g in &self.groups {
            let (f, m) = match *g {
                Group::One(i) => (forces[i], moments[i]),
                Group::Two([i, j]) => (forces[i] + forces[j], moments[i] + moments[j]),
                Group::Four([a, c, b, d]) => (
                    (forces[a] + forces[c]) + (forces[b] + forces[d]),
                    (moments[a] + moments[c]) + (moments[b] + moments[d]),
                ),
            };
            force += f;
            moment += m;
        }
        (force, moment)
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
        for g in &self.groups {
            let group = match *g {
                Group::One(i) => term(i),
                Group::Two([i, j]) => add(term(i), term(j)),
                Group::Four([a, c, b, d]) => add(add(term(a), term(c)), add(term(b), term(d))),
            };
            total = add(total, group);
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

    /// [`SumOrder::sum_loads`] of `t` as the forces, with `t` reversed as the moments: each
    /// the sum [`SumOrder::sum_by`] gives, bit for bit.
    fn sum(order: &SumOrder, t: &[Vector3<f64>]) -> Vector3<f64> {
        let reversed: Vec<_> = t.iter().rev().copied().collect();
        let (force, moment) = order.sum_loads(t, &reversed);
        assert_eq!(force, order.sum_by(Vector3::zeros(), |i| t[i]));
        assert_eq!(moment, order.sum_by(Vector3::zeros(), |i| reversed[i]));
        force
    }

    /// Three legs of a square and a fourth at (x, y).
    fn legs(x: f64, y: f64) -> [Leg; 4] {
        [leg(1.0, 1.0), leg(-1.0, 1.0), leg(-1.0, -1.0), leg(x, y)]
    }

    #[test]
    fn renumbered_legs_sum_alike() {
        let legs = legs(1.0, -1.0);
        let t = terms();
        let reference = sum(&SumOrder::new(&legs), &t);
        for shift in 1..4 {
            let map: Vec<usize> = (0..4).map(|k| (k + shift) % 4).collect();
            let renumbered: Vec<Leg> = map.iter().map(|&i| legs[i]).collect();
            let moved: Vec<_> = map.iter().map(|&i| t[i]).collect();
            assert_eq!(sum(&SumOrder::new(&renumbered), &moved), reference);
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
            sum(&SumOrder::new(&image), &mirrored),
            mirror(&sum(&SumOrder::new(&legs), &t))
        );
        // Twins (±x) are summed as a pair, singles alone.
        assert_eq!(SumOrder::new(&legs).groups.len(), 3);
    }

    #[test]
    fn a_ring_of_four_sums_alike_under_every_turn_and_mirror_of_its_square() {
        // The report's gear: legs at quarter turns; the eight maps of the square onto itself
        // (turns by quarters, mirrors in the axes and the diagonals), each exact on x and y.
        let square = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
        let legs: Vec<Leg> = square.iter().map(|&(x, y)| leg(x, y)).collect();
        let t = terms();
        type Map = fn(&Vector3<f64>) -> Vector3<f64>;
        let maps: [Map; 8] = [
            |v| *v,
            |v| Vector3::new(-v.y, v.x, v.z),
            |v| Vector3::new(-v.x, -v.y, v.z),
            |v| Vector3::new(v.y, -v.x, v.z),
            |v| Vector3::new(-v.x, v.y, v.z),
            |v| Vector3::new(v.x, -v.y, v.z),
            |v| Vector3::new(v.y, v.x, v.z),
            |v| Vector3::new(-v.y, -v.x, v.z),
        ];
        let reference = sum(&SumOrder::new(&legs), &t);
        for g in maps {
            let image: Vec<Leg> = legs.iter().map(|l| leg(g(&l.b2).x, g(&l.b2).y)).collect();
            let moved: Vec<_> = t.iter().map(g).collect();
            assert_eq!(sum(&SumOrder::new(&image), &moved), g(&reference));
        }
        assert_eq!(SumOrder::new(&legs).groups.len(), 1);
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
