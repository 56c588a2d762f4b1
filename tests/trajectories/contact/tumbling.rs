//! A box tumbling onto the floor: four corner contacts opening and
//! closing in any order, with friction and restitution.

use lagrange::contact::Cause;
use lagrange::models::TumblingBox;

use super::{run, times};

#[test]
fn a_tumbling_box_never_penetrates_and_never_gains_energy() {
    let (m, w, h) = (2.0, 0.6, 0.3);
    let boxed = TumblingBox::new(m, w, h, 9.81, 0.4, 0.5);
    // Dropped from 0.5 m, tilted and spinning, drifting sideways.
    let start = ([0.0, 0.5, 0.3], [0.8, 0.0, 4.0]);
    let samples = times(3.0, 600);
    let run = run(&boxed, start, &samples).unwrap();
    let impacts = run
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::Impact)
        .count();
    assert!(impacts >= 3, "{:?}", run.switches());
    let e0 = boxed.energy(0.0, &start.0.into(), &start.1.into());
    let mut previous = e0;
    for sample in run.trajectory().iter() {
        // No corner below the floor beyond the integration's drift of a
        // closed contact (1e-10 at this tolerance) or a located arrival.
        let gaps = lagrange::contact::Contacts::gaps(&boxed, sample.t, &sample.q);
        if gaps.min() < -1e-9 {
            for s in run
                .switches()
                .iter()
                .filter(|s| s.t > 0.6 && s.t < sample.t)
            {
                let g = lagrange::contact::Contacts::gaps(&boxed, s.t, &s.q);
                let gd = lagrange::contact::Contacts::gap_velocities(&boxed, s.t, &s.q, &s.qdot);
                println!(
                    "{:.12} {} {:?}->{:?} {:?} g={:?} gdot={:?}",
                    s.t,
                    s.name,
                    s.from,
                    s.to,
                    s.cause,
                    g.as_slice(),
                    gd.as_slice()
                );
            }
            println!("sample t={} g={:?}", sample.t, gaps.as_slice());
        }
        assert!(
            gaps.min() > -1e-9,
            "a corner at {} at t = {}",
            gaps.min(),
            sample.t
        );
        // Energy only falls: friction and restitution take it, workless
        // contacts keep it, to the method's 1e-12 of the 10 J scale.
        let e = boxed.energy(sample.t, &sample.q, &sample.qdot);
        assert!(
            e <= previous + 1e-10,
            "energy rose from {previous} to {e} at t = {}",
            sample.t
        );
        previous = e;
    }
    for impact in run.switches().iter().filter(|s| s.cause == Cause::Impact) {
        assert!(
            impact.energy_lost >= 0.0,
            "an impact gained {}",
            -impact.energy_lost
        );
    }
}
