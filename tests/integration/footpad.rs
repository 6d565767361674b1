//! Footpads with inertia (`footpad.detached = "inertial"`; docs/errata.md, "Footpads with
//! inertia"): every footpad is a point mass in every phase. Off the surface it stays above its
//! plane, in contact the surface only pushes, it lands as an impact of its own mass and leaves
//! with its gear still loaded, a wall holds it laterally until it clears it, and its landings
//! and take-offs are motions of a body, not a switch at the step rate.

use std::sync::atomic::{AtomicUsize, Ordering};
use touchdown_core::ContactState;
use touchdown_core::{Landing, Observer, Simulation};
use touchdown_scenario::Scenario;

/// How far below its plane a footpad off the surface may be at an accepted state, m.
const BELOW_PLANE: f64 = 1e-5;

/// Scenario `base` (under scenarios/) with footpads with inertia and `extra` TOML on top.
fn inertial(base: &str, extra: &str) -> Scenario {
    static MADE: AtomicUsize = AtomicUsize::new(0);
    let n = MADE.fetch_add(1, Ordering::Relaxed);
    let name = format!("inertial-{n}-{}", base.trim_end_matches(".toml"));
    let extra = format!("[footpad]\ndetached = \"inertial\"\n{extra}");
    let path = touchdown_tests::variant(base, &name, &extra);
    Scenario::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Every bundled landing (scenarios/*.toml).
fn landings() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(touchdown_tests::root().join("scenarios"))
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    names
}

/// What a run shows of its footpads at every accepted state: the deepest a footpad off the
/// surface went below its plane (m), the least normal reaction on one in contact (N), and per
/// leg the times its contact changed.
struct Footpads {
    planes: Vec<f64>,
    weight: f64,
    below: f64,
    least_reaction: f64,
    changes: Vec<Vec<f64>>,
    last: Vec<bool>,
}

impl Footpads {
    fn new(sc: &Scenario) -> Footpads {
        let n = sc.legs.len();
        let g = touchdown_frames::gravity_inertial(sc.vehicle.gravity, sc.surface.slope);
        Footpads {
            planes: sc.surface.pads.iter().map(|p| p.plane()).collect(),
            weight: -sc.footpad.mass * g.z,
            below: 0.0,
            least_reaction: f64::INFINITY,
            changes: vec![Vec::new(); n],
            last: vec![false; n],
        }
    }
}

impl Observer<Simulation> for Footpads {
    fn observe(&mut self, sim: &Simulation) {
        let t_bi = sim.vehicle().t_bi;
        for (i, (p, g)) in sim.footpads().iter().zip(sim.gear()).enumerate() {
            let contact = p.state == ContactState::Contact;
            if contact {
                // eqs. (67), (85): FZI, positive pressing, plus the footpad's weight
                let reaction = -(t_bi * g.fp).z + self.weight;
                self.least_reaction = self.least_reaction.min(reaction);
            } else {
                self.below = self.below.max(self.planes[i] - p.position.z);
            }
            if contact != self.last[i] {
                self.changes[i].push(sim.time());
                self.last[i] = contact;
            }
        }
    }
}

/// On every bundled landing on a rigid surface, with footpads with inertia, at every accepted
/// state: no footpad off the surface is more than 0.01 mm below its plane, the surface never
/// pulls on a footpad in contact (beyond the contact logic's force rounding), and every run
/// ends with its energy balance within its guard (it stops otherwise).
#[test]
fn inertial_footpads_stay_above_their_planes_and_are_only_pushed() {
    let mut checked = 0;
    for name in landings() {
        let sc = inertial(&name, "");
        if sc.surface.soil.is_some() {
            continue; // a footpad penetrates soil (eq. 103)
        }
        let mut watch = Footpads::new(&sc);
        Simulation::new(&sc)
            .and_then(|mut s| s.run(&mut watch))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let crush = sc.primary.compression.stages.last().unwrap().0;
        assert!(
            watch.below <= BELOW_PLANE,
            "{name}: a footpad {:.3e} m below its plane",
            watch.below
        );
        assert!(
            watch.least_reaction >= -1e-9 * crush,
            "{name}: the surface pulled with {:.3e} N",
            watch.least_reaction
        );
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} landings checked");
}

/// The landings whose massless footpads left and landed again every 0.3-0.4 ms (250 contact
/// changes per leg on fig-25-26, 371 on the 1-2-1 landing at 7 ft/s): with inertia every
/// flight lasts at least 1 ms (the effective footpad's periods on its gear are 3.6-9.3 ms), and
/// so does every spell on the surface but one graze a leg at most: a footpad that comes down
/// while its gear is already turning to lift it stops in a plastic impact and leaves as soon as
/// the surface would have to pull it. Standing on spikes that let them go, the footpads hop as
/// the vehicle rocks, so a leg changes contact as often as the rocking lasts: 26 times, leg 4 of
/// the 1-2-1 landing at 7 ft/s until 1.10 s (its shortest spell 1.6 ms, its shortest flight
/// 16 ms). How long the rocking lasts is no law of the footpad: with the core's arithmetic
/// changed at rounding level (docs/errata.md, "The 2-2 landing, its own mirror image") leg 2
/// changes 57 times, and with FS1 refitted to that arithmetic 45 times (shortest flights 1.8
/// and 5.0 ms); so no count is asserted, only the spells. On
/// `fig-25-26` the uphill footpads are on the surface 1.3, 3.2 and 0.10 ms at 0.067, 0.082 and
/// 0.095 s (the graze: it comes down at 3.7 m/s), in flight 14.5 and 9.1 ms between. A changes
/// list starts with a landing (every footpad starts off its surface), so its even spells are
/// on the surface.
#[test]
fn inertial_footpads_land_and_leave_as_bodies() {
    for name in ["fig-25-26.toml", "table-i-1-2-1-vv7.toml"] {
        let sc = inertial(name, "");
        let mut watch = Footpads::new(&sc);
        let mut sim = Simulation::new(&sc).unwrap();
        sim.run(&mut watch).unwrap();
        for (leg, times) in watch.changes.iter().enumerate() {
            let mut grazes = 0;
            for (k, spell) in times.windows(2).enumerate() {
                let on_surface = k % 2 == 0;
                if spell[1] - spell[0] < 1e-3 {
                    grazes += 1;
                    assert!(
                        on_surface && grazes == 1,
                        "{name} leg {}: a {} of {:.3e} s from {:.5} s",
                        leg + 1,
                        if on_surface { "second graze" } else { "flight" },
                        spell[1] - spell[0],
                        spell[0]
                    );
                }
            }
        }
    }
}

/// A vertical drop on level ground lands its four footpads at t = 0 in plastic impacts of
/// their own mass: the contact events take exactly their normal kinetic energy, Σ ½·PMASS·v_z².
#[test]
fn a_landing_footpad_loses_its_normal_kinetic_energy() {
    let sc = inertial("flat-drop.toml", "");
    let sim = Simulation::new(&sc).unwrap();
    let touched = sim.footpads().iter().filter(|p| p.first_contact.is_some());
    let vz = sim.vehicle().velocity.z;
    let expected = -(touched.count() as f64) * 0.5 * sc.footpad.mass * vz * vz;
    assert!(expected < 0.0);
    let events = sim.energy().contact_events_j;
    assert!(
        (events - expected).abs() <= 1e-12 * expected.abs(),
        "{events} J against {expected} J"
    );
}

/// The strokes of a gear whose footpad leaves the surface carry on from where they were:
/// between two accepted states around a release each stroke moves by no more than its rate
/// allows over the step (a massless gear relaxed to zero force jumped by millimetres there),
/// and the stored energy goes where the laws send it.
#[test]
fn a_leaving_footpad_keeps_its_gear_loaded() {
    /// Per leg: in contact, primary stroke (m), its rate (m/s).
    type Legs = Vec<(bool, f64, f64)>;
    struct Release {
        last: Option<(f64, Legs)>,
        releases: usize,
        worst: f64,
    }
    impl Observer<Simulation> for Release {
        fn observe(&mut self, sim: &Simulation) {
            let now: Vec<_> = sim
                .footpads()
                .iter()
                .zip(sim.gear())
                .map(|(p, g)| {
                    let contact = p.state == ContactState::Contact;
                    (contact, g.primary_stroke, g.primary_rate)
                })
                .collect();
            if let Some((t, before)) = &self.last {
                let dt = sim.time() - t;
                for (a, b) in before.iter().zip(&now) {
                    if a.0 && !b.0 {
                        self.releases += 1;
                        let allowed = 1.5 * a.2.abs().max(b.2.abs()) * dt + 1e-9;
                        self.worst = self.worst.max((b.1 - a.1).abs() / allowed);
                    }
                }
            }
            self.last = Some((sim.time(), now));
        }
    }
    for name in [
        "table-i-1-2-1-vv7.toml",
        "table-i-2-2-vv8.toml",
        "fig-25-26.toml",
    ] {
        let sc = inertial(name, "");
        let mut watch = Release {
            last: None,
            releases: 0,
            worst: 0.0,
        };
        Simulation::new(&sc).unwrap().run(&mut watch).unwrap();
        assert!(watch.releases > 0, "{name}: no footpad left its surface");
        assert!(
            watch.worst <= 1.0,
            "{name}: a primary stroke jumped {:.2} times what its rate allows at a release",
            watch.worst
        );
    }
}

/// An obstacle's wall (OBST > 0) holds a footpad laterally from its landing until it rises
/// above the wall (text after fig. 17), on the surface or off it: with a 1 ft wall no footpad
/// that has landed moves sideways on the 1-2-1 landing at 7 ft/s; with a 0.03 mm wall the
/// footpads that leave clear it and move.
#[test]
fn a_wall_holds_a_footpad_until_it_clears_it() {
    struct Lateral {
        landed: Vec<Option<(f64, f64)>>,
        moved: f64,
    }
    impl Observer<Simulation> for Lateral {
        fn observe(&mut self, sim: &Simulation) {
            for (i, p) in sim.footpads().iter().enumerate() {
                if p.state == ContactState::Contact && self.landed[i].is_none() {
                    self.landed[i] = Some((p.position.x, p.position.y));
                }
                if let Some((x, y)) = self.landed[i] {
                    let d = ((p.position.x - x).powi(2) + (p.position.y - y).powi(2)).sqrt();
                    self.moved = self.moved.max(d);
                }
            }
        }
    }
    let moved = |wall: f64| {
        let sc = inertial(
            "table-i-1-2-1-vv7.toml",
            &format!("[surface]\nspike_depth = 0.0\nobstacle = {wall}\n"),
        );
        let mut watch = Lateral {
            landed: vec![None; sc.legs.len()],
            moved: 0.0,
        };
        Simulation::new(&sc).unwrap().run(&mut watch).unwrap();
        watch.moved
    };
    assert_eq!(moved(1.0), 0.0, "a footpad moved inside a 1 ft wall");
    assert!(moved(1e-4) > 1e-3, "no footpad cleared a 0.03 mm wall");
}

/// The landing whose energy balance did not converge with massless footpads (−0.86 % with the
/// default step, −3.5 to −4.2 % with finer ones), and an asymmetric variant that stopped on the
/// energy guard on the report's scheme, complete on every scheme with inertial footpads.
#[test]
fn every_scheme_lands_the_bending_landing_and_its_asymmetric_variant() {
    let asymmetric = "[touchdown]\nattitude = [5.0, 0.0, 62.0]\n\
                      horizontal_velocity = [2.4, 5.2]\nbody_rates = [11.46, -8.59, 17.19]\n";
    for extra in ["", asymmetric] {
        for scheme in ["report", "rk4", "dopri5"] {
            let sc = inertial(
                "bending-2-2-vv8.toml",
                &format!("{extra}[integrator]\nscheme = \"{scheme}\"\n"),
            );
            let summary = Simulation::new(&sc)
                .and_then(|mut s| s.run(&mut ()))
                .unwrap_or_else(|e| panic!("{scheme} {extra}: {e}"));
            let e = &summary.energy;
            assert!(
                e.residual_j.abs() <= sc.integrator.energy_tolerance * e.scale(),
                "{scheme} {extra}: residual {} J",
                e.residual_j
            );
        }
    }
}

/// Table I landings on which the report's scheme does not close the balance within 1 % with a
/// stroke-out stop a hundred times stiffer, an open defect (docs/errata.md, "Footpads with
/// inertia", "Numerics"). With the footpads held by 1 ft walls, the 1-2-1 landings whose
/// trailing footpads hung on their primaries' extension stops ended at 2.39 J (7 ft/s), 3.73 J
/// of 235 J (1.6 %, 10 ft/s) and 4.00 J of 310 J (1.3 %, 13 ft/s). The defect moves with the
/// stops' law, the restraint and the calibration. On spikes, at the calibration refitted when
/// the 2-2 landings were made their own mirror images (FS1 −0.27 %), the 1-2-1 landings at 7
/// and 13 ft/s close within 1 % (+1.70 J of 189 J at 7 ft/s, which stopped on its guard at
/// 0.211 s before) and four stop on their energy guard with a primary on its elastic rebound:
/// the slow landings, whose footpads fly free of their spikes, 1-2-1 at 5 ft/s (+11.3 J of
/// 176 J at 0.154 s), 2-2 at 4 ft/s (+19.4 J of 140 J at 0.138 s) and 6 ft/s (+4.4 J of 194 J
/// at 0.163 s), and 1-2-1 at 10 ft/s (+5.6 J of 227 J at 0.483 s, leg 3; it closed before).
const STIFF_STOP_BALANCE: &[&str] = &[
    "table-i-1-2-1-vv10.toml",
    "table-i-1-2-1-vv5.toml",
    "table-i-2-2-vv4.toml",
    "table-i-2-2-vv6.toml",
];

/// The report's scheme takes a free footpad's axial mode on its primary implicitly: a
/// footpad hanging on an extension stop a hundred times stiffer does not shorten the step
/// (the explicit schemes' bound, 0.5/ω of that mode, would be 10 times shorter) and, on every
/// Table I landing but those of [`STIFF_STOP_BALANCE`], the balance still closes within 1 %.
#[test]
fn the_report_scheme_takes_the_footpads_stiff_axial_mode_implicitly() {
    let stiff = "[primary_strut.compression]\nstroke_out_rate = 87000000.0\n";
    for name in touchdown_tests::validation_landings() {
        if !name.starts_with("table-i") {
            continue;
        }
        let run = |extra: &str| {
            let sc = inertial(&name, extra);
            Simulation::new(&sc).unwrap().run(&mut ())
        };
        let default = run("").unwrap_or_else(|e| panic!("{name}: {e}"));
        let stiffer = run(stiff);
        if STIFF_STOP_BALANCE.contains(&name.as_str()) {
            // Listed as open: the defect must still show, or the list is out of date.
            let closes = stiffer
                .as_ref()
                .is_ok_and(|s| s.energy.residual_j.abs() <= 1e-2 * s.energy.scale());
            assert!(!closes, "{name} now closes: take it off STIFF_STOP_BALANCE");
            continue;
        }
        let stiffer = stiffer.unwrap_or_else(|e| panic!("{name}, stiff stop: {e}"));
        let e = &stiffer.energy;
        assert!(
            e.residual_j.abs() <= 1e-2 * e.scale(),
            "{name}: residual {} J of {} J",
            e.residual_j,
            e.scale()
        );
        assert!(
            (stiffer.steps as f64) < 1.1 * default.steps as f64,
            "{name}: {} steps with the stiffer stop against {}",
            stiffer.steps,
            default.steps
        );
    }
}
