//! The `hostile` command as a person (or `.ci/run`) runs it: a clean run
//! passes and says how many scenes it ran, a failing scene fails the run
//! (unless its class is tolerated) and is written out for replay, and bad
//! arguments are refused with a message that names them.

use std::process::{Command, Output};

fn hostile(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hostile"))
        .args(args)
        .output()
        .expect("the hostile binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

#[test]
fn a_clean_run_of_every_kind_passes_and_counts_its_scenes() {
    let out = hostile(&["--count", "32", "--seed", "0", "--jobs", "2"]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", text(&out.stderr));
    assert!(
        stdout.contains("32 scenes (2 per kind), 0 failed"),
        "{stdout}"
    );
}

#[test]
fn a_failing_scene_fails_the_run_unless_tolerated_and_is_written_out() {
    // Cluster 183 runs into the event cap under revision 3 (fixed in 4).
    let dir = tempfile::tempdir().expect("a scratch folder");
    let dump = dir.path().to_str().expect("a UTF-8 path");
    let base = [
        "--kind",
        "cluster",
        "--seed",
        "183",
        "--count",
        "1",
        "--revision",
        "r3",
    ];
    let out = hostile(&[&base[..], &["--dump", dump]].concat());
    let stdout = text(&out.stdout);
    assert!(!out.status.success(), "{stdout}");
    assert!(stdout.contains("| cluster | livelock | 1 |"), "{stdout}");
    assert!(dir.path().join("cluster-183.json").is_file());

    let out = hostile(&[&base[..], &["--tolerate", "livelock,slow"]].concat());
    assert!(out.status.success(), "{}", text(&out.stdout));

    let out = hostile(&["--kind", "cluster", "--seed", "183", "--count", "1"]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    assert!(
        stdout.contains("1 scenes (1 per kind), 0 failed"),
        "{stdout}"
    );
}

#[test]
fn bad_arguments_are_refused_with_a_message_naming_them() {
    for (args, says) in [
        (
            &["--revision", "r99"][..],
            "no engine revision named \"r99\"",
        ),
        (
            &["--tolerate", "sloth"][..],
            "--tolerate \"sloth\": no such failure",
        ),
        (&["--kind", "blob"][..], "--kind \"blob\": no such kind"),
        (
            &["--count", "lots"][..],
            "invalid value 'lots' for '--count <COUNT>'",
        ),
    ] {
        let out = hostile(args);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{args:?} was accepted");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
    }
}
