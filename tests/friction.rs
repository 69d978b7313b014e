//! Coulomb friction on contact pairs (node-to-segment and segment-integrated), as a whole: a ring shrunk on a tube (0.05 mm
//! radial interference, both held axially at their faces) is then pushed axially along it by
//! moving its two faces together. While it sticks, the push force is below mu N and no node
//! slides; slip starts at the ring's ends and spreads inward (the ring's own axial stiffness
//! lets its ends go first); once every node slides, the push force equals mu times the normal
//! contact force to 1e-6 (each node at its Coulomb limit). Also: 1 and 2 ranks agree, and bad
//! friction input is refused. (The module's deck holds the tube rigid for the Coulomb law; the
//! rank test lets it deform.)

mod common;
use common::{pushed_fit_deck as deck_with, run_deck, Results, TIGHT};

const MU: f64 = 0.2;

/// The fit and the push; `tube` holds the tube: its faces axially (a deformable tube) or all
/// its nodes (a rigid one).
fn deck(push: f64, increments: usize, friction: &str) -> String {
    deck_with(push, increments, friction, r#"{ set = "tube_bottom", uz = 0.0 }, { set = "tube_top", uz = 0.0 }"#)
}

const RIGID_TUBE: &str = r#"{ set = "tube", ur = 0.0, uz = 0.0 }"#;

/// (push force, normal force) per radian and the number of sliding nodes, per increment.
fn push_history(r: &Results) -> Vec<(f64, f64, usize)> {
    let (bottom, top, normal) = (r.history("reaction_ring_bottom_z"), r.history("reaction_ring_top_z"), r.history("contact_fit_force"));
    (0..normal.len())
        .map(|k| {
            let name = format!("increments/{:06}/contact/fit/pass0/sliding", k + 1);
            // (written for pairs with friction only)
            let sliding = if r.file.link_exists(&name) { r.u8s(&name).iter().filter(|&&s| s == 1).count() } else { 0 };
            (bottom[k] + top[k], normal[k], sliding)
        })
        .collect()
}

#[test]
fn a_pushed_shrink_fit_sticks_below_mu_n_and_slides_at_mu_n() {
    for integration in ["node-to-segment", "segment"] {
        pushed_fit(integration, &format!("friction = {MU}"));
    }
}

/// The same with the stick stiffness from an elastic slip (eps_T = mu p / gamma, gamma = 50
/// nm: the push of 20 nm an increment sticks for two increments, then slides).
#[test]
fn with_an_elastic_slip_the_pushed_fit_also_sticks_below_mu_n_and_slides_at_mu_n() {
    for integration in ["node-to-segment", "segment"] {
        pushed_fit(integration, &format!("friction = {MU}\nelastic_slip = 5.0e-5"));
    }
}

fn pushed_fit(integration: &str, friction: &str) {
    let with = |text: String| text.replace("integration = \"node-to-segment\"", &format!("integration = \"{integration}\""));
    // on a rigid tube the contact normal stays radial, so the push force is the friction force
    // alone (on an elastic tube its surface tilts by ~1e-6 under the shear and the normal force
    // adds 1e-5 of mu N)
    let run = run_deck(&with(deck_with(2.0e-4, 10, friction, RIGID_TUBE)), &[], 1, TIGHT);
    run.assert_ok();
    let r = Results::open(&run.h5);
    let rows = push_history(&r);
    let nodes = r.u8s("increments/000001/contact/fit/pass0/active").len();
    let (mut stuck, mut slid) = (0, 0);
    for (k, &(push, normal, sliding)) in rows.iter().enumerate().skip(1) {
        assert!(normal > 2000.0, "{integration} #{}: the fit holds ({normal} N/rad)", k + 1);
        let ratio = push / (MU * normal);
        assert!(ratio > 0.0 && ratio <= 1.0 + 1e-6, "{integration} #{}: |F| <= mu N ({ratio})", k + 1);
        if sliding == 0 {
            stuck += 1;
            assert!(ratio < 0.99, "{integration} #{}: no node slides, yet F = {ratio} mu N", k + 1);
        }
        if sliding == nodes {
            slid += 1;
            assert!((ratio - 1.0).abs() < 1e-6, "{integration} #{}: every node slides: F = mu N to 1e-6, got {ratio}", k + 1);
        }
    }
    assert!(stuck >= 1 && slid >= 3, "{integration}: the push sticks first ({stuck} increments), then slides ({slid})");
    // and mu times the Lame fit pressure over the bore: on a rigid shaft (r = a = 110) a ring
    // to b = 125, held axially (plane strain), with radial interference delta = 0.05 has
    // u(a) = delta = (1 + nu) a p / E ((1 - 2 nu) a^2 + b^2) / (b^2 - a^2)
    let (a, b, nu, e, delta, length) = (110.0f64, 125.0f64, 0.3, 200000.0, 0.05, 4.0);
    let p_lame = delta * e / ((1.0 + nu) * a * ((1.0 - 2.0 * nu) * a * a + b * b) / (b * b - a * a));
    let expected = MU * p_lame * a * length; // per radian
    let last = rows.last().unwrap().0;
    assert!((last / expected - 1.0).abs() < 0.02, "{integration}: push force {last} N/rad against mu p_Lame r L = {expected} (p_Lame {p_lame} MPa)");
    // frictionless, the same push needs no force at all
    let run = run_deck(&with(deck_with(2.0e-4, 2, "", RIGID_TUBE)), &[], 1, &[]);
    run.assert_ok();
    let rows = push_history(&Results::open(&run.h5));
    assert!(rows.last().unwrap().0.abs() < 1e-6 * rows.last().unwrap().1, "{rows:?}");
}

#[test]
fn one_and_two_ranks_agree_with_friction() {
    let text = deck(2.0e-4, 10, &format!("friction = {MU}\ntangential_penalty = 5.0e4"));
    let one = run_deck(&text, &[], 1, TIGHT);
    one.assert_ok();
    let two = run_deck(&text, &[], 2, TIGHT);
    two.assert_ok();
    let (a, b) = (push_history(&Results::open(&one.h5)), push_history(&Results::open(&two.h5)));
    for (x, y) in a.iter().zip(&b) {
        assert!((x.0 - y.0).abs() <= 1e-8 * x.1 && (x.1 - y.1).abs() <= 1e-8 * x.1 && x.2 == y.2, "{x:?} vs {y:?}");
    }
}

#[test]
fn bad_friction_input_is_refused() {
    for (friction, needle) in [
        ("friction = -0.1", "friction coefficient -0.1"),
        ("tangential_penalty = 1.0e4", "tangential_penalty without friction"),
        ("friction = 0.2\ntangential_penalty = 0.0", "tangential_penalty 0"),
        ("elastic_slip = 0.001", "elastic_slip without friction"),
        ("friction = 0.2\nelastic_slip = -0.001", "elastic_slip -0.001"),
        ("friction = 0.2\ntangential_penalty = 1.0e4\nelastic_slip = 0.001", "not both"),
    ] {
        let run = run_deck(&deck(1e-4, 1, friction), &[], 1, &[]);
        assert_eq!(run.code(), 2, "{friction}: {}", run.stderr());
        assert!(run.stderr().contains(needle), "{friction}: {}", run.stderr());
    }
}

#[test]
fn a_run_with_friction_continues_bit_identically_from_a_restart() {
    // the slip references (where each node's slip is measured from) are part of the state
    let text = deck(2.0e-4, 10, &format!("friction = {MU}"));
    let full = run_deck(&text, &[], 1, &[]);
    full.assert_ok();
    let deck_path = full.dir.path().join("deck.toml");
    let continued = full.dir.path().join("continued.h5");
    let out = common::command_in(full.dir.path(), 1)
        .arg("run")
        .arg(&deck_path)
        .args(["--restart", full.h5.to_str().unwrap(), "--increment", "5", "-q", "-o", continued.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    common::assert_continues(&full.h5, &continued, 5);
}

/// A changed friction acts from its step's start: the fit pushed on at mu = 0.2, then (step
/// 3, `contact_friction`) at mu = 0.1, then frictionless. Sliding at each step's end, the push
/// force is mu N of the step's mu (to 1e-6: every node at its Coulomb limit), and zero without
/// friction; a restart inside the step of mu = 0.1 continues with it, bit for bit. A pair
/// frictionless at first takes friction from the push on (its slip measured from where the
/// nodes are when the step starts).
#[test]
fn a_friction_changed_in_a_step_acts_from_its_start_and_survives_a_restart() {
    let more_steps = r#"[[step]]
name = "lighter"
increments = 4
boundary = [ { set = "ring_bottom", uz = 4.0e-4 }, { set = "ring_top", uz = 4.0e-4 } ]
contact_friction = [ { pair = "fit", friction = 0.1 } ]
[[step]]
name = "frictionless"
increments = 2
boundary = [ { set = "ring_bottom", uz = 5.0e-4 }, { set = "ring_top", uz = 5.0e-4 } ]
contact_friction = [ { pair = "fit", friction = 0.0 } ]
"#;
    for integration in ["node-to-segment", "segment"] {
        let with = |text: String| text.replace("integration = \"node-to-segment\"", &format!("integration = \"{integration}\""));
        let text = with(deck_with(2.0e-4, 5, &format!("friction = {MU}"), RIGID_TUBE)) + more_steps;
        let full = run_deck(&text, &[], 1, TIGHT);
        full.assert_ok();
        let r = Results::open(&full.h5);
        let rows = push_history(&r);
        let step = r.history("step");
        let last_of = |s: f64| step.iter().rposition(|&k| k == s).unwrap();
        let mu_n = |row: usize, mu: f64| {
            let (push, normal, _) = rows[row];
            assert!((push / (mu * normal) - 1.0).abs() < 1e-6, "{integration} #{}: push {push} N/rad against mu N = {}", row + 1, mu * normal);
        };
        mu_n(last_of(2.0), MU);
        // the lighter step's first increment already slides at the new mu
        mu_n(last_of(2.0) + 1, 0.1);
        mu_n(last_of(3.0), 0.1);
        let (push, normal, _) = rows[last_of(4.0)];
        assert!(push.abs() < 1e-6 * normal, "{integration}: frictionless: push {push} N/rad");
        // a restart inside step 3 continues with mu = 0.1
        let continued = full.dir.path().join("continued.h5");
        let out = common::command_in(full.dir.path(), 1)
            .arg("run")
            .arg(full.dir.path().join("deck.toml"))
            .args(["--restart", full.h5.to_str().unwrap(), "--increment", &(last_of(2.0) + 2).to_string(), "-q", "-o", continued.to_str().unwrap()])
            .args(TIGHT)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        common::assert_continues(&full.h5, &continued, last_of(2.0) + 2);

        // frictionless at first, friction from the push on
        let text = with(deck_with(2.0e-4, 5, "", RIGID_TUBE))
            .replace("name = \"push\"\n", &format!("name = \"push\"\ncontact_friction = [ {{ pair = \"fit\", friction = {MU} }} ]\n"));
        let run = run_deck(&text, &[], 1, TIGHT);
        run.assert_ok();
        let rows = push_history(&Results::open(&run.h5));
        let (push, normal, _) = *rows.last().unwrap();
        assert!((push / (MU * normal) - 1.0).abs() < 1e-6, "{integration}: friction turned on: push {push} N/rad against mu N = {}", MU * normal);
    }
}

#[test]
fn assembled_jacobian_with_friction_matches_finite_differences_for_both_integrations_one_and_two_pass() {
    // PETSc's -snes_test_jacobian at every Newton iterate, on 2 ranks: the pushed fit on an
    // elastic tube, through stick and slip
    for (integration, two_pass) in [("node-to-segment", false), ("segment", false), ("node-to-segment", true), ("segment", true)] {
        assert_jacobian_matches(integration, two_pass, &format!("friction = {MU}"));
    }
}

#[test]
fn assembled_jacobian_with_an_elastic_slip_matches_finite_differences_for_both_integrations() {
    // as above, with eps_T = mu p / gamma: the tangent carries the stiffness's dependence on
    // the pressure (through the integrated pressure's gap gradient for segment integration)
    for integration in ["node-to-segment", "segment"] {
        assert_jacobian_matches(integration, false, &format!("friction = {MU}\nelastic_slip = 2.0e-5"));
    }
}

/// Runs the pushed fit (`friction` lines) with -snes_test_jacobian on 2 ranks and checks the
/// assembled Jacobian against PETSc's finite differences.
fn assert_jacobian_matches(integration: &str, two_pass: bool, friction: &str) {
    let integration_line = format!("integration = \"{integration}\"\ntwo_pass = {two_pass}");
    let text = deck(1.2e-4, 4, friction).replace("integration = \"node-to-segment\"", &integration_line);
    let what = format!("{integration}{}, {}", if two_pass { ", two-pass" } else { "" }, friction.replace('\n', ", "));
    let run = run_deck(&text, &[], 2, &["--", "-snes_test_jacobian"]);
    run.assert_ok();
    let all = common::jacobian_test_ratios(&run.stdout());
    assert!(all.len() >= 4, "{what}: PETSc printed no Jacobian test");
    // the first iterate (u = 0, the fit's 0.05 mm interference at once) is left out: there
    // the frictionless deck's Jacobian differs from the differences by 1.4e-3 as well, and
    // by 1.5e-6 at the second (the fit's large first correction); the push's iterates are
    // at 2e-8
    let ratios = &all[1..];
    let worst = ratios.iter().copied().fold(0.0, f64::max);
    let push_worst = ratios[1..].iter().copied().fold(0.0, f64::max);
    println!("{what}: {} Jacobian tests, worst ||J - Jfd|| / ||J|| = {worst:e}, from the third on {push_worst:e}", ratios.len());
    assert!(worst < 2e-6 && push_worst < 1e-7, "{what}: {ratios:?}");
}

/// Newton with friction converges quadratically once the stick/slip states have settled:
/// the shrink fit (elastic tube) pushed 20 um in 2 increments, so that each increment takes the
/// interface from sticking to gross sliding and Newton, without a predictor, has iterations to judge. After the last
/// slow step of an increment (e_(k+1) > e_k / 10: states still changing), every step from
/// e_k < 0.1 to above the round-off floor (10 x the final residual) has e_(k+1) <= e_k^2,
/// e = ||F|| / ||F_0||. Measured: 3.3e-2 -> 9.5e-5 -> 7.9e-10; with the friction tangent
/// scaled by 0.7 (a wrong tangent, friction being a small part of the Jacobian) 7.4e-5 ->
/// 7.7e-7, which fails.
#[test]
fn newton_converges_quadratically_while_the_fit_slides() {
    let tube = r#"{ set = "tube_bottom", uz = 0.0 }, { set = "tube_top", uz = 0.0 }"#;
    for integration in ["node-to-segment", "segment"] {
        // no predictor: Newton itself takes the interface from sticking to sliding (the
        // tangent predictor, friction's tractions held, lands within 2e-5 of the answer)
        let text = deck_with(2.0e-2, 2, &format!("friction = {MU}"), tube)
            .replace("integration = \"node-to-segment\"", &format!("integration = \"{integration}\""))
            + "[stepping]\npredictor = \"none\"\n";
        let run = run_deck(&text, &[], 1, TIGHT);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let mut checked = 0;
        for inc in res.increments().iter().skip(1) {
            let r = res.f64s(&format!("{inc}/residual_norms"));
            let e: Vec<f64> = r.iter().map(|v| v / r[0]).collect();
            let floor = 10.0 * e.last().unwrap();
            let settled = e.windows(2).rposition(|w| w[1] > 0.1 * w[0] && w[1] > floor).map_or(0, |k| k + 1);
            for w in e[settled..].windows(2).filter(|w| w[0] < 0.1 && w[1] > floor) {
                assert!(w[1] <= w[0] * w[0], "{integration} {inc}: {} -> {} is not quadratic; norms {r:?}", w[0], w[1]);
                checked += 1;
            }
        }
        assert!(checked >= 2, "{integration}: too few asymptotic iterations to judge");
    }
}

/// What ParaView shows of friction (2 ranks, the slave nodes split between them): at the nodes,
/// `friction_shear` and `contact_sliding` are each slave node's shear and sliding flag of its
/// pass, 0 at every other node, in every increment.
#[test]
fn friction_shear_and_sliding_are_at_the_nodes_for_paraview() {
    let text = deck(2.0e-4, 10, &format!("friction = {MU}\ntangential_penalty = 5.0e4"));
    let run = run_deck(&text, &[], 2, &[]);
    run.assert_ok();
    let r = Results::open(&run.h5);
    let nodes = r.u64s("mesh/contact/fit/pass0/nodes");
    let (mut slid, mut stuck) = (0, 0);
    for inc in r.increments() {
        let (shear, sliding) = (r.f64s(&format!("{inc}/contact/fit/pass0/shear")), r.u8s(&format!("{inc}/contact/fit/pass0/sliding")));
        let (nodal_shear, nodal_sliding) = (r.f64s(&format!("{inc}/nodal/friction_shear")), r.f64s(&format!("{inc}/nodal/contact_sliding")));
        let mut expected = (vec![0.0; nodal_shear.len()], vec![0.0; nodal_shear.len()]);
        for (k, &n) in nodes.iter().enumerate() {
            expected.0[n as usize] = shear[k];
            expected.1[n as usize] = f64::from(sliding[k]);
        }
        assert_eq!((nodal_shear, nodal_sliding), expected, "{inc}");
        slid += sliding.iter().filter(|&&s| s == 1).count();
        stuck += sliding.iter().filter(|&&s| s == 0).count();
    }
    assert!(slid > 0 && stuck > 0, "both sticking and sliding nodes were checked ({stuck}, {slid})");
}
