//! A scene advanced frame by frame at 60 Hz: the same switches as one
//! `integrate`, each reported in the frame it falls in; and a model with
//! contacts refused by the runs that would ignore them.

use lagrange::InvalidInput;
use lagrange::contact::{ContactSettings, Scene};
use lagrange::models::{BallOnFloor, BlockOnBelt};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

#[test]
fn a_stepper_at_sixty_hertz_reports_the_switches_of_integrate_each_in_its_frame() {
    let block = BlockOnBelt::new(1.0, 9.81, 40.0, 0.3, 0.6, 0.4);
    let ball = BallOnFloor::new(1.0, 9.81, 0.5);
    let method = Dop853::new().rtol(1e-12).atol(1e-12);
    let settings = ContactSettings::default();
    let belt_scene = Scene::new(
        &block,
        0.0,
        Vector2::zeros(),
        Vector2::new(0.3, 0.0),
        settings,
    )
    .unwrap();
    let ball_scene = Scene::new(
        &ball,
        0.0,
        Vector2::new(0.0, 1.0),
        Vector2::zeros(),
        settings,
    )
    .unwrap();
    let frames = 180;
    let end = frames as f64 / 60.0;

    let whole = belt_scene.integrate(&method, &[end]).unwrap();
    let mut stepper = belt_scene.stepper(method).unwrap();
    let mut reported = Vec::new();
    for frame in 1..=frames {
        let (from, to) = (stepper.t(), frame as f64 / 60.0);
        stepper.advance_to(to).unwrap();
        for event in stepper.events() {
            assert!(
                from < event.t && event.t <= to,
                "frame {frame} reports t = {}",
                event.t
            );
            reported.push(event.t);
        }
    }
    compare(whole.switches(), stepper.switches(), &reported);

    let whole = ball_scene.integrate(&method, &[end]).unwrap();
    let mut stepper = ball_scene.stepper(method).unwrap();
    let mut reported = Vec::new();
    for _ in 1..=frames {
        stepper.advance(1.0 / 60.0).unwrap();
        reported.extend(stepper.events().iter().map(|e| e.t));
    }
    compare(whole.switches(), stepper.switches(), &reported);
}

/// The same switches in the same order, their times within 1e-9 (the
/// frames cut the stepper's steps where `integrate`'s are not cut: the
/// trajectories differ by the method's error, 1e-12, and the ball's last
/// flights are shorter than that error can shift), and every switch after
/// the start reported by the stepper in its frame.
fn compare<const N: usize>(
    whole: &[lagrange::contact::Switch<f64, N>],
    framed: &[lagrange::contact::Switch<f64, N>],
    reported: &[f64],
) {
    assert_eq!(whole.len(), framed.len(), "{whole:?}\n{framed:?}");
    assert!(whole.len() > 4);
    for (a, b) in whole.iter().zip(framed) {
        assert_eq!(
            (a.contact, a.cause, a.from, a.to),
            (b.contact, b.cause, b.from, b.to)
        );
        assert!((a.t - b.t).abs() < 1e-9, "{} against {}", a.t, b.t);
    }
    for switch in framed.iter().filter(|s| s.t > 0.0) {
        assert!(
            reported.contains(&switch.t),
            "the switch at {} was not reported",
            switch.t
        );
    }
}

/// Each run of a scene owns its modes and switches: two steppers advanced
/// in turn, with a whole `integrate` of the same scene between their
/// frames, end bit for bit where one stepper alone ends. (When the modes
/// were the scene's, shared by its runs behind a lock, each `integrate`
/// set them back to the start's under the steppers' feet.)
#[test]
fn runs_of_one_scene_in_turn_each_keep_their_own_modes_and_switches() {
    let block = BlockOnBelt::new(1.0, 9.81, 40.0, 0.3, 0.6, 0.4);
    let scene = Scene::new(
        &block,
        0.0,
        Vector2::zeros(),
        Vector2::new(0.3, 0.0),
        ContactSettings::default(),
    )
    .unwrap();
    let method = Dop853::new().rtol(1e-10).atol(1e-10);
    let frame = |k: usize| k as f64 / 60.0;
    let (frames, lag) = (180, 30);

    let mut alone = scene.stepper(method).unwrap();
    for k in 1..=frames {
        alone.advance_to(frame(k)).unwrap();
    }
    assert!(alone.switches().len() > 4, "{:?}", alone.switches());

    let mut first = scene.stepper(method).unwrap();
    let mut second = scene.stepper(method).unwrap();
    for k in 1..=frames + lag {
        if k <= frames {
            first.advance_to(frame(k)).unwrap();
        }
        if k > lag {
            second.advance_to(frame(k - lag)).unwrap();
        }
        let whole = scene.integrate(&method, &[frame(k)]).unwrap();
        assert_eq!(whole.switches()[0], scene.start_switches()[0]);
    }
    for stepper in [&first, &second] {
        assert_eq!(stepper.switches(), alone.switches());
        assert_eq!(stepper.modes(), alone.modes());
        assert_eq!((stepper.q(), stepper.qdot()), (alone.q(), alone.qdot()));
    }
}

#[test]
fn a_model_with_contacts_is_refused_by_the_runs_that_would_ignore_them() {
    let ball = BallOnFloor::new(1.0, 9.81, 0.5);
    let (q, v) = (Vector2::new(0.0, 1.0), Vector2::zeros());
    let failure = Rk4::new(1e-3)
        .integrate(&ball, 0.0, q, v, &[1.0])
        .unwrap_err();
    assert!(
        matches!(
            failure.error,
            IntegrationError::InvalidInput(InvalidInput::ContactsNotRun)
        ),
        "{}",
        failure.error
    );
    assert!(
        failure
            .error
            .to_string()
            .contains("lagrange::contact::integrate")
    );
    assert!(Stepper::new(ball, Rk4::new(1e-3), 0.0, q, v).is_err());
}
