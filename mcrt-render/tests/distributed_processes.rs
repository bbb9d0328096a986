//! Distributed rendering with the examples as separate processes (issue 14), as
//! `docs/distributed.md` runs them: several `render --samples/--crop` processes at once, then
//! `merge`, whose image equals the single render's; `merge` refuses a gap with exit status 1;
//! `render` names parts by their share and refuses what cannot be split.

mod distributed_common;

use distributed_common::{example, max_ulps, scratch};
use mcrt_render::film::{read_exr, read_part, SampleRange};
use std::path::Path;
use std::process::{Command, Stdio};

/// The arguments of a small render of the built-in Cornell box.
fn render_args(dir: &Path, out: &str, extra: &[&str]) -> Vec<String> {
    let mut a: Vec<String> = ["-D", "res=32", "--spp", "8", "--threads", "1", "-o"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    a.push(dir.join(out).display().to_string());
    a.extend(extra.iter().map(|s| s.to_string()));
    a
}

#[test]
fn render_processes_in_parallel_and_merge_give_the_single_render() {
    let dir = scratch("processes");
    let jobs: [&[&str]; 4] = [
        &[],
        &["--samples", "0..3"],
        &["--samples", "3..8", "--crop", "0,0,32,11"],
        &["--samples", "3..8", "--crop", "0,11,32,32"],
    ];
    let names = ["whole.exr", "p0.exr", "p1.exr", "p2.exr"];
    // Every render at once, each in its own process.
    let children: Vec<_> = jobs
        .iter()
        .zip(names)
        .map(|(extra, out)| {
            Command::new(example("render"))
                .args(render_args(&dir, out, extra))
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .expect("render starts")
        })
        .collect();
    for c in children {
        let out = c.wait_with_output().expect("render ends");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let merge = |args: &[&str]| {
        Command::new(example("merge"))
            .args(args.iter().map(|a| dir.join(a)))
            .output()
            .expect("merge runs")
    };
    let out = merge(&["merged.exr", "p0.exr", "p1.exr", "p2.exr"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.join("merged.png").is_file());
    let (_, _, whole) = read_exr(&dir.join("whole.exr")).expect("whole");
    let (_, _, merged) = read_exr(&dir.join("merged.exr")).expect("merged");
    let d = max_ulps(&merged, &whole);
    assert!(d <= 1, "{d} ulps");
    // A gap: refused with status 1, naming the missing samples; nothing written.
    let out = merge(&["gap.exr", "p0.exr", "p1.exr"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("pixel (0, 11) lacks samples 3..8"), "{err}");
    assert!(!dir.join("gap.exr").exists());
    // An output that is one of the parts is refused.
    let out = merge(&["p0.exr", "p0.exr", "p1.exr", "p2.exr"]);
    assert_eq!(out.status.code(), Some(1));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_render_example_names_parts_and_refuses_what_cannot_be_split() {
    let dir = scratch("cli");
    let run = |args: &[&str]| {
        Command::new(example("render"))
            .current_dir(&dir)
            .args(args)
            .output()
            .expect("render runs")
    };
    // Without -o a part goes to renders/ with its share in its name.
    let out = run(&[
        "-D",
        "res=16",
        "--spp",
        "2",
        "--samples",
        "1..2",
        "--crop",
        "0,0,8,16",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let part = dir.join("renders/cornell-box.samples-1-2.crop-0-0-8-16.exr");
    let p = read_part(&part).expect("a part");
    assert_eq!(p.info.samples, SampleRange { start: 1, end: 2 });
    for (args, says) in [
        (&["--samples", "1-2"][..], "START..END"),
        (&["--samples", "0..2", "-o", "x.png"], "must end in .exr"),
        (&["--crop", "0,0,4,4", "--variance"], "merge --variance"),
        (
            &["--integrator", "mlt", "--crop", "0,0,4,4"],
            "mlt cannot be split",
        ),
        (&["-D", "resolution=16"], "\"resolution\""),
    ] {
        let out = run(args);
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
