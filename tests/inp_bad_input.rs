//! Abaqus/CalculiX decks outside slideline's subset, or wrong, are refused with one message
//! naming the file, the line and the keyword (exit code 2), before anything runs.

mod common;
use common::{assert_rejected, command_in, Run};

/// A small valid deck; `{MODEL}` and `{STEP}` are replaced by extra model and step lines.
const DECK: &str = "*HEADING
one CAX8 ring
*NODE
1, 10., 0.
2, 12., 0.
3, 12., 2.
4, 10., 2.
5, 11., 0.
6, 12., 1.
7, 11., 2.
8, 10., 1.
*ELEMENT, TYPE=CAX8, ELSET=RING
1, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=BOTTOM
1, 5, 2
*NSET, NSET=TOP
4, 7, 3
{MODEL}*MATERIAL, NAME=STEEL
*ELASTIC
200000., 0.3
*SOLID SECTION, ELSET=RING, MATERIAL=STEEL
*BOUNDARY
BOTTOM, 2, 2
*STEP
*STATIC
1., 1.
*BOUNDARY
TOP, 2, 2, 0.01
{STEP}*END STEP
";

fn run_inp(model: &str, step: &str, files: &[(&str, &str)]) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let deck = DECK.replace("{MODEL}", model).replace("{STEP}", step);
    std::fs::write(dir.path().join("model.inp"), deck).unwrap();
    for (name, text) in files {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    let h5 = dir.path().join("out.h5");
    let output = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "model.inp", "-o"]).arg(&h5).output().unwrap();
    Run { dir, output, h5 }
}

#[test]
fn the_valid_deck_runs_and_says_how_it_was_read() {
    let run = run_inp("", "", &[]);
    run.assert_ok();
    let out = run.stdout();
    assert!(out.contains("1 CAX8 elements run as slideline's 8-node"), "{out}");
    assert!(out.contains("2-degree segment"), "{out}");
}

#[test]
fn an_unsupported_keyword_is_named_with_its_line() {
    let run = run_inp("*ORIENTATION, NAME=ORI\n1., 0., 0., 0., 1., 0.\n", "", &[]);
    assert_rejected(&run, &["model.inp:18", "*ORIENTATION", "outside the subset"]);
}

#[test]
fn an_unsupported_keyword_inside_a_step_is_named_with_its_line() {
    let run = run_inp("", "*DSLOAD\nTOP, P, 100.\n", &[]);
    assert_rejected(&run, &["model.inp:29", "*DSLOAD"]);
}

#[test]
fn a_missing_include_is_named_with_its_line() {
    let run = run_inp("*INCLUDE, INPUT=materials.inc\n", "", &[]);
    assert_rejected(&run, &["model.inp:18", "materials.inc"]);
}

#[test]
fn an_error_inside_an_include_names_the_included_file_and_its_line() {
    let run = run_inp("*INCLUDE, INPUT=extra.inc\n", "", &[("extra.inc", "** extra sets\n*NSET, NSET=OUTER\n2, 6, 99\n")]);
    assert_rejected(&run, &["extra.inc:3", "node 99"]);
}

#[test]
fn an_element_type_outside_the_subset_is_named_with_its_line() {
    let run = run_inp("*ELEMENT, TYPE=C3D8, ELSET=SOLID\n2, 1, 2, 3, 4, 5, 6, 7, 8\n", "", &[]);
    assert_rejected(&run, &["model.inp:18", "C3D8", "CAX8", "CPS"]);
}

#[test]
fn a_set_used_before_it_is_defined_is_named_with_its_line() {
    let run = run_inp("*NSET, NSET=BOTH\nBOTTOM, LATER\n*NSET, NSET=LATER\n3\n", "", &[]);
    assert_rejected(&run, &["model.inp:19", "LATER", "not defined"]);
}

#[test]
fn a_surface_used_in_a_contact_pair_before_it_is_defined_is_named() {
    let model = "*SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.e5\n*CONTACT PAIR, INTERACTION=I, TYPE=SURFACE TO SURFACE\nINNER, OUTER\n";
    let run = run_inp(model, "", &[]);
    assert_rejected(&run, &["model.inp:22", "INNER", "not defined"]);
}

#[test]
fn friction_it_cannot_honour_and_other_pressure_overclosure_laws_are_refused() {
    let model = "*SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n";
    assert_rejected(&run_inp(model, "", &[]), &["model.inp:19", "HARD"]);
    // the exponential law needs c0 > 0, and is built for node-to-surface pairs
    let model = "*SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=EXPONENTIAL\n0., .1\n";
    assert_rejected(&run_inp(model, "", &[]), &["model.inp:19", "c0 > 0", "c0 = 0"]);
    let pairs = with_pairs("*CONTACT PAIR, INTERACTION=I, TYPE=SURFACE TO SURFACE\nIN, OUT\n")
        .replace("PRESSURE-OVERCLOSURE=LINEAR\n1.e5", "PRESSURE-OVERCLOSURE=EXPONENTIAL\n1.e-4, .1");
    assert_rejected(&run_inp(&pairs, "", &[]), &["IN-OUT", "exponential", "node-to-segment"]);
    // Coulomb friction (mu[, stick slope]) is read; Abaqus' other friction models are not
    let model = "*SURFACE INTERACTION, NAME=I\n*FRICTION, SLIP TOLERANCE=0.005\n0.2\n";
    assert_rejected(&run_inp(model, "", &[]), &["model.inp:19", "SLIP TOLERANCE"]);
    let model = "*SURFACE INTERACTION, NAME=I\n*FRICTION\n-0.2\n";
    assert_rejected(&run_inp(model, "", &[]), &["model.inp:19", "friction coefficient -0.2"]);
}

#[test]
fn an_unknown_parameter_is_refused_rather_than_ignored() {
    let run = run_inp("*NSET, NSET=X, UNSORTED\n1\n", "", &[]);
    assert_rejected(&run, &["model.inp:18", "UNSORTED"]);
}

/// The ring's bore and outside as contact surfaces, with `pairs` (*CONTACT PAIR cards) after.
fn with_pairs(pairs: &str) -> String {
    format!("*SURFACE, NAME=IN, TYPE=ELEMENT\n1, S4\n*SURFACE, NAME=OUT, TYPE=ELEMENT\n1, S2\n*SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.e5\n{pairs}")
}

#[test]
fn an_adjust_set_off_the_slave_surface_is_named() {
    let run = run_inp(&with_pairs("*CONTACT PAIR, INTERACTION=I, ADJUST=TOP\nIN, OUT\n"), "", &[]);
    assert_rejected(&run, &["contact 'IN-OUT'", "adjust set 'TOP'", "not on the slave surface 'IN'"]);
}

#[test]
fn a_negative_adjust_is_refused_with_its_line() {
    let run = run_inp(&with_pairs("*CONTACT PAIR, INTERACTION=I, ADJUST=-0.1\nIN, OUT\n"), "", &[]);
    assert_rejected(&run, &["model.inp:", "ADJUST=-0.1", ">= 0"]);
}

#[test]
fn adjust_on_the_reversed_listing_of_a_two_pass_pair_is_refused() {
    let run = run_inp(&with_pairs("*CONTACT PAIR, INTERACTION=I\nIN, OUT\n*CONTACT PAIR, INTERACTION=I, ADJUST=0.1\nOUT, IN\n"), "", &[]);
    assert_rejected(&run, &["model.inp:", "give ADJUST on the first listing"]);
}

/// `*STEP, INC=0` allows no increment at all: refused with its line (it was accepted).
#[test]
fn a_step_allowed_no_increment_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("model.inp"), DECK.replace("{MODEL}", "").replace("{STEP}", "").replace("*STEP\n", "*STEP, INC=0\n")).unwrap();
    let output = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "model.inp", "-o", "out.h5"]).output().unwrap();
    let run = Run { h5: dir.path().join("out.h5"), dir, output };
    assert_rejected(&run, &["model.inp:24", "*STEP", "INC=0", ">= 1"]);
}

/// What CalculiX's own decks hold beyond slideline's physics is refused with its reason:
/// fluid networks, heat transfer.
#[test]
fn cards_of_other_physics_are_refused_with_their_reason() {
    for (model, step, needles) in [
        ("*ELEMENT, TYPE=D, ELSET=F\n2, 1, 2, 3\n", "", ["model.inp:18", "type D", "no fluid networks"]),
        ("*FLUID CONSTANTS\n1., 1.\n", "", ["model.inp:18", "*FLUID CONSTANTS", "no fluid networks"]),
        ("", "*FILM\nRING, F1, 20., 1.\n", ["model.inp:29", "*FILM", "heat steps hold temperatures"]),
    ] {
        let run = run_inp(model, step, &[]);
        assert_rejected(&run, &needles);
    }
}

/// Heat-transfer cards in the wrong place: a temperature held in a static step, a heat step
/// after a static one, a conductivity that varies with temperature, a transient heat step.
#[test]
fn a_misplaced_heat_card_is_named() {
    let heat_step = "*END STEP\n*STEP\n*HEAT TRANSFER, STEADY STATE\n*BOUNDARY\nTOP, 11, 11, 100.\n";
    for (model, step, needles) in [
        ("", "*BOUNDARY\nTOP, 11, 11, 50.\n", vec!["*STEP", "a temperature (*BOUNDARY, 11) outside a *HEAT TRANSFER step"]),
        ("*MATERIAL, NAME=HOT\n*CONDUCTIVITY\n50., 20.\n45., 200.\n", "", vec!["model.inp:19", "*CONDUCTIVITY", "varies with temperature"]),
        ("", heat_step, vec!["step step-2", "a *HEAT TRANSFER step after a *STATIC step"]),
        ("", "*END STEP\n*STEP\n*HEAT TRANSFER\n", vec!["*HEAT TRANSFER", "transient heat transfer", "STEADY STATE"]),
        (
            "*MATERIAL, NAME=WARM\n*CONDUCTIVITY\n50.\n*STEP\n*HEAT TRANSFER, STEADY STATE\n*BOUNDARY\nTOP, 11, 11, 100.\n*END STEP\n",
            "",
            vec!["material 'WARM' has no elastic constants", "*ELASTIC"],
        ),
    ] {
        let run = run_inp(model, step, &[]);
        assert_rejected(&run, &needles);
    }
}

/// Constraint cards name what is wrong in them: a degree of freedom outside the plane, an
/// equation short of its terms, a tie between surfaces that are not there or too far apart, a
/// beam's pre-tension.
#[test]
fn a_wrong_constraint_card_is_named() {
    for (model, needles) in [
        ("*EQUATION\n2\n3, 3, 1., 7, 2, -1.\n", ["model.inp:18", "*EQUATION", "degree of freedom 3"]),
        ("*EQUATION\n3\n3, 2, 1., 7, 2, -1.\n", ["model.inp:19", "3 terms announced, 2 given", "*EQUATION"]),
        ("*EQUATION\n2\n3, 2, 1., 99, 2, -1.\n", ["model.inp:20", "node 99 is not defined", "*EQUATION"]),
        ("*SURFACE, NAME=UP\n1, S3\n*TIE, NAME=T\nUP, NOWHERE\n", ["model.inp:20", "*TIE", "surface NOWHERE is not defined"]),
        (
            "*SURFACE, NAME=UP\n1, S3\n*SURFACE, NAME=DOWN\n1, S1\n*TIE, NAME=T, POSITION TOLERANCE=0.1\nUP, DOWN\n",
            ["model.inp:22", "tie T", "within 1.000e-1 mm"],
        ),
        ("*PRE-TENSION SECTION, ELEMENT=1, NODE=1\n", ["model.inp:18", "*PRE-TENSION SECTION", "no beam elements"]),
        ("*PRE-TENSION SECTION, SURFACE=NONE, NODE=1\n", ["model.inp:18", "*PRE-TENSION SECTION", "surface NONE is not defined"]),
    ] {
        assert_rejected(&run_inp(model, "", &[]), &needles);
    }
}

/// Material data a static step does not use and physical constants are read and said to have
/// no effect, point masses to carry only the loads given on them (CalculiX's ring3 and mass3
/// carry them).
#[test]
fn thermal_material_data_and_point_masses_are_accepted_with_a_note() {
    let model = "*ELEMENT, TYPE=MASS, ELSET=M\n5, 3\n*MASS, ELSET=M\n1.e-3\n*PHYSICAL CONSTANTS, ABSOLUTE ZERO=-273.15\n\
                 *MATERIAL, NAME=OTHER\n*ELASTIC\n1000., 0.3\n*CONDUCTIVITY\n50.\n*SPECIFIC HEAT\n4.6e8\n";
    let run = run_inp(model, "", &[]);
    run.assert_ok();
    let out = run.stdout();
    for needle in ["*CONDUCTIVITY", "*SPECIFIC HEAT", "*PHYSICAL CONSTANTS", "the point masses of M carry only the GRAV and CENTRIF loads"] {
        assert!(out.contains(needle), "{needle}: {out}");
    }
    let run = run_inp("*MASS, ELSET=RING\n1.e-3\n", "", &[]);
    assert_rejected(&run, &["model.inp:18", "RING holds no elements of type MASS"]);
}

/// CalculiX 2.20's axisymmetric test decks, each with the reader's verdict: `None`, it runs (and
/// scripts/calculix-test-decks.sh compares it with ccx); or the model and step lines holding the
/// card it refuses first, with the text naming it, which the docs' table must name too.
type Verdict = Option<(&'static str, &'static str, &'static str)>;
const HEAT_TRANSFER: Verdict = Some(("", "*HEAT TRANSFER\n1., 1.\n", "transient heat transfer"));
const HEAT_GENERATION: Verdict = Some(("*SURFACE INTERACTION, NAME=I1\n*GAP HEAT GENERATION\n1., 1.\n", "", "*GAP HEAT GENERATION"));
const NETWORK: Verdict = Some(("*ELEMENT, TYPE=D, ELSET=F\n2, 1, 2, 3\n", "", "type `D`"));
const CALCULIX_AXISYMMETRIC_DECKS: [(&str, Verdict); 20] = [
    ("ring1", None),
    ("ring2", None),
    ("axial", None),
    ("mass3", None),
    ("ax6", None),
    ("axiplane", None),
    ("ax6ht", None),
    ("axrad", HEAT_TRANSFER),
    ("bolt", None),
    ("pret2", None),
    ("thread", None),
    ("ring3", HEAT_GENERATION),
    ("ring4", HEAT_GENERATION),
    ("artery1", NETWORK),
    ("artery2", NETWORK),
    ("artery3", NETWORK),
    ("artery4", NETWORK),
    ("artery5", NETWORK),
    ("gaspres", NETWORK),
    ("axrad2", Some(("*NODE\n9, 1., 2., 3.\n", "", "third coordinate"))),
];

/// The table of CalculiX's decks in docs/inp.md lists every deck above once, says "runs" for
/// those that run, and names the card the reader refuses first for the others; the reader
/// refuses that card with its name.
#[test]
fn the_docs_table_of_calculix_decks_matches_the_readers_verdicts() {
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/inp.md")).unwrap();
    let start = docs.find("| deck | what it tests |").expect("the table of CalculiX's decks");
    let mut rows: Vec<(String, String)> = Vec::new();
    for line in docs[start..].lines().skip(2).take_while(|l| l.starts_with('|')) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        for name in cells[1].split(", ") {
            // "artery1..5" is artery1 to artery5
            let names: Vec<String> = match name.split_once("..") {
                Some((first, last)) => {
                    let stem = first.trim_end_matches(|c: char| c.is_ascii_digit());
                    let from: usize = first[stem.len()..].parse().unwrap();
                    (from..=last.parse().unwrap()).map(|k| format!("{stem}{k}")).collect()
                }
                None => vec![name.to_string()],
            };
            rows.extend(names.into_iter().map(|n| (n, cells[3].to_string())));
        }
    }
    let mut listed: Vec<&str> = rows.iter().map(|r| r.0.as_str()).collect();
    listed.sort_unstable();
    let mut decks: Vec<&str> = CALCULIX_AXISYMMETRIC_DECKS.iter().map(|d| d.0).collect();
    decks.sort_unstable();
    assert_eq!(listed, decks, "the table lists each of CalculiX's 20 axisymmetric decks once");
    for (deck, verdict) in CALCULIX_AXISYMMETRIC_DECKS {
        let said = &rows.iter().find(|r| r.0 == deck).unwrap().1;
        match verdict {
            None => assert!(said.starts_with("runs"), "{deck}: the table says {said:?}, the reader runs it"),
            Some((model, step, card)) => {
                assert!(said.contains(card), "{deck}: the table says {said:?}, the reader refuses {card}");
                let run = run_inp(model, step, &[]);
                assert_rejected(&run, &[&card.replace('`', "")]);
            }
        }
    }
}

/// A short *ELEMENT line is named itself, with the count it has (the reader took the next
/// line as its continuation and blamed that one with a wrong count); a line ending with a comma
/// still continues. An empty deck (or one of comments) is called empty (it said "no
/// *MATERIAL"). A node far out (r = 1e308) is named at the node (the element's Jacobian was
/// blamed).
#[test]
fn a_short_element_line_an_empty_deck_and_a_far_node_are_named() {
    let short = DECK.replace("1, 1, 2, 3, 4, 5, 6, 7, 8\n", "1, 1, 2, 3, 4, 5, 6, 7\n2, 1, 2, 3, 4, 5, 6, 7, 8\n").replace("{MODEL}", "").replace("{STEP}", "");
    let split = DECK.replace("1, 1, 2, 3, 4, 5, 6, 7, 8\n", "1, 1, 2, 3, 4,\n5, 6, 7, 8\n").replace("{MODEL}", "").replace("{STEP}", "");
    let far = DECK.replace("3, 12., 2.\n", "3, 1e308, 2.\n").replace("{MODEL}", "").replace("{STEP}", "");
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, text: &str| {
        std::fs::write(dir.path().join(name), text).unwrap();
        command_in(dir.path(), 1).current_dir(dir.path()).args(["run", name, "-o", "out.h5"]).output().unwrap()
    };
    let refused = |out: std::process::Output, needles: &[&str]| {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(needles.iter().all(|n| stderr.contains(n)) && stderr.lines().count() == 1, "{needles:?}: {stderr}");
    };
    refused(run("short.inp", &short), &["short.inp:13: *ELEMENT: CAX8 takes 8 nodes after the element number, this line has 7"]);
    assert!(run("split.inp", &split).status.success(), "a line ending with a comma continues");
    refused(run("empty.inp", ""), &["empty.inp: the deck is empty"]);
    refused(run("comments.inp", "** nothing\n**\n"), &["comments.inp: the deck is empty"]);
    refused(run("far.inp", &far), &["node 3 at (1e308, 2e0): coordinates beyond 1e9 mm"]);
}

/// *PLASTIC, HARDENING=KINEMATIC is Prager's linear rule from a two-point curve; a longer
/// curve (multilinear kinematic hardening) and HARDENING=COMBINED are refused with the line.
#[test]
fn kinematic_hardening_beyond_a_two_point_curve_is_refused_with_its_line() {
    let plastic = |card: &str| {
        let dir = tempfile::tempdir().unwrap();
        let deck = DECK.replace("{MODEL}", "").replace("{STEP}", "").replace("200000., 0.3\n", &format!("200000., 0.3\n{card}"));
        std::fs::write(dir.path().join("model.inp"), deck).unwrap();
        let h5 = dir.path().join("out.h5");
        let output = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "model.inp", "-o"]).arg(&h5).output().unwrap();
        Run { dir, output, h5 }
    };
    let three = plastic("*PLASTIC, HARDENING=KINEMATIC\n200., 0.\n300., 0.01\n350., 0.05\n");
    assert_rejected(&three, &["model.inp:21", "*PLASTIC", "two-point curve", "3 points"]);
    let combined = plastic("*PLASTIC, HARDENING=COMBINED\n200., 0.\n300., 0.01\n");
    assert_rejected(&combined, &["model.inp:21", "ISOTROPIC or KINEMATIC"]);
    // the two-point curve is read, and says how
    let two = plastic("*PLASTIC, HARDENING=KINEMATIC\n200., 0.\n300., 0.01\n");
    two.assert_ok();
    assert!(two.stdout().contains("linear kinematic hardening of slope 10000 MPa"), "{}", two.stdout());
}
