//! Output that is never lost (issue 11): the output plan decided and checked before
//! rendering, partial images under their own names, identical bytes for identical renders,
//! and the `render` program's process behaviour (`--help`, exit status 130 on SIGINT and
//! SIGTERM with `NAME.partial.exr` written).

use mcrt::glam::Vec3;
use mcrt_render::film::{read_exr, write_exr, Film, OutputPlan, PixelAccum, EXIT_INTERRUPTED};
use mcrt_render::render::{RenderOptions, Renderer};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

/// A scratch folder for this test, empty.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mcrt-output-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    std::fs::create_dir_all(&d).expect("scratch folder");
    d
}

#[test]
fn the_extension_chooses_the_format_and_the_other_goes_beside_it() {
    let p = OutputPlan::new(Some(Path::new("d/x.png")), "s", None, true).expect("png");
    assert_eq!(
        (p.exr.as_path(), p.png.as_path()),
        (Path::new("d/x.exr"), Path::new("d/x.png"))
    );
    assert_eq!(p.variance.as_deref(), Some(Path::new("d/x-variance.exr")));
    let p = OutputPlan::new(Some(Path::new("x.EXR")), "s", None, false).expect("exr");
    assert_eq!(
        (p.exr.as_path(), p.png.as_path()),
        (Path::new("x.EXR"), Path::new("x.png"))
    );
    let p = OutputPlan::new(None, "cornell-box", None, false).expect("default");
    assert_eq!(p.exr, Path::new("renders/cornell-box.exr"));
    let partial = p.partial();
    assert_eq!(
        (partial.exr.as_path(), partial.png.as_path()),
        (
            Path::new("renders/cornell-box.partial.exr"),
            Path::new("renders/cornell-box.partial.png")
        )
    );
    for bad in ["x.jpg", "x", "x.exr.tmp"] {
        assert!(
            OutputPlan::new(Some(Path::new(bad)), "s", None, false).is_err(),
            "{bad}"
        );
    }
}

#[test]
fn an_output_equal_to_the_scene_file_is_refused() {
    let dir = scratch("same");
    let scene = dir.join("scene.png");
    std::fs::write(&scene, "<scene version=\"3.0.0\"/>").expect("scene written");
    for out in ["scene.png", "scene.exr", "./scene.png"] {
        let out = dir.join(out);
        let e = OutputPlan::new(Some(&out), "scene", Some(&scene), false).unwrap_err();
        assert!(e.to_string().contains("is the scene file"), "{e}");
    }
    assert!(OutputPlan::new(Some(&dir.join("other.exr")), "s", Some(&scene), false).is_ok());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_unwritable_output_is_refused_before_rendering() {
    let p = OutputPlan::new(Some(Path::new("/nonexistent/x.exr")), "s", None, false)
        .expect("a well-formed name");
    let e = p.check_writable().unwrap_err();
    assert!(e.to_string().contains("/nonexistent"), "{e}");
    let dir = scratch("writable");
    std::fs::create_dir_all(dir.join("x.exr")).expect("a folder named x.exr");
    let p = OutputPlan::new(Some(&dir.join("x.exr")), "s", None, false).expect("name");
    assert!(p
        .check_writable()
        .unwrap_err()
        .to_string()
        .contains("is a folder"));
    let p = OutputPlan::new(Some(&dir.join("y.exr")), "s", None, true).expect("name");
    p.check_writable().expect("a writable folder");
    // The check leaves nothing behind.
    let names: Vec<_> = std::fs::read_dir(&dir).expect("dir").collect();
    assert_eq!(names.len(), 1);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_interrupted_render_never_replaces_the_complete_image() {
    let dir = scratch("partial");
    let plan = OutputPlan::new(Some(&dir.join("img.exr")), "s", None, true).expect("plan");
    let mut film = Film::new(2, 1);
    let mut a = PixelAccum::default();
    a.add(Vec3::splat(0.25));
    film.merge(0, &a).expect("inside");
    film.merge(1, &a).expect("inside");
    let complete = plan.write(&film, false).expect("complete write");
    assert_eq!(
        complete,
        [
            dir.join("img.exr"),
            dir.join("img.png"),
            dir.join("img-variance.exr")
        ]
    );
    let before = std::fs::read(&plan.exr).expect("complete image");
    // A second render interrupted with pixel 1 unsampled.
    let mut film = Film::new(2, 1);
    film.merge(0, &a).expect("inside");
    let partial = plan.write(&film, true).expect("partial write");
    assert_eq!(
        partial,
        [
            dir.join("img.partial.exr"),
            dir.join("img.partial.png"),
            dir.join("img-variance.partial.exr")
        ]
    );
    assert_eq!(std::fs::read(&plan.exr).expect("complete image"), before);
    let (w, h, px) = read_exr(&dir.join("img.partial.exr")).expect("partial image");
    assert_eq!((w, h), (2, 1));
    assert!(px[0].is_finite() && (px[0] - Vec3::splat(0.25)).length() < 1e-6);
    assert!(px[1].is_nan(), "an unsampled pixel is marked: {}", px[1]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn same_arguments_give_the_same_bytes() {
    let dir = scratch("bytes");
    let desc = mcrt_render::cornell_box::cornell_box_with(1, 256, -1);
    let opts = RenderOptions {
        seed: Some(7),
        ..RenderOptions::default()
    };
    let mut files = Vec::new();
    for k in 0..2 {
        let out = Renderer::new(&desc, &opts)
            .expect("scene builds")
            .render(&|_, _| {}, &AtomicBool::new(false));
        assert_eq!(out.nonfinite_samples, 0);
        let p = dir.join(format!("r{k}.exr"));
        out.write_exr(&p).expect("exr written");
        files.push(std::fs::read(&p).expect("exr bytes"));
    }
    assert_eq!(files[0], files[1]);
    // Writing the same pixels many times (compression runs in parallel) gives one file.
    let px: Vec<Vec3> = (0..512 * 512)
        .map(|i| Vec3::new((i % 97) as f32, (i % 13) as f32 * 0.1, 0.5))
        .collect();
    let p = dir.join("same.exr");
    write_exr(&p, 512, 512, &px).expect("written");
    let first = std::fs::read(&p).expect("bytes");
    for _ in 0..4 {
        write_exr(&p, 512, 512, &px).expect("written");
        assert!(std::fs::read(&p).expect("bytes") == first);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The `render` program, which Cargo builds for this package's integration tests.
fn render_example() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_render"))
}

#[test]
fn help_lists_every_option_with_its_default_and_exits_0() {
    let out = Command::new(render_example())
        .arg("--help")
        .output()
        .expect("render --help runs");
    assert!(out.status.success(), "{:?}", out.status);
    let text = String::from_utf8_lossy(&out.stdout);
    for option in [
        "--spp",
        "-D",
        "-o",
        "--threads",
        "--seed",
        "--variance",
        "--strategy",
        "--sampler",
        "--accel",
        "--light-sampling",
        "--help",
    ] {
        assert!(text.contains(option), "{option} missing from:\n{text}");
    }
    assert!(text.matches("[default:").count() >= 11, "{text}");
}

#[test]
fn a_bad_output_fails_before_rendering() {
    let start = Instant::now();
    let out = Command::new(render_example())
        .args(["-D", "spp=100000", "-o", "/nonexistent/x.exr"])
        .output()
        .expect("render runs");
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent"));
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
}

/// Starts a long render, sends `signal` once it has begun, and checks exit status 130 and
/// the partial files.
fn interrupted_by(signal: &str) {
    let dir = scratch(&format!("signal-{signal}"));
    let out = dir.join("box.png");
    let mut child = Command::new(render_example())
        .args(["-D", "spp=100000", "-D", "res=64", "--threads", "1", "-o"])
        .arg(&out)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("render starts");
    // The header line is printed once the signal handler is installed, just before
    // rendering.
    let mut header = String::new();
    // Kept open until the end: the render prints more when it stops.
    let mut stdout = BufReader::new(child.stdout.take().expect("piped stdout"));
    stdout.read_line(&mut header).expect("header line");
    assert!(header.contains("spp"), "{header}");
    std::thread::sleep(Duration::from_millis(200));
    let sent = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
    let status = child.wait().expect("render ends");
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stdout, &mut rest).expect("the rest of stdout");
    assert!(rest.contains("interrupted"), "{rest}");
    assert_eq!(status.code(), Some(i32::from(EXIT_INTERRUPTED)), "{signal}");
    assert!(dir.join("box.partial.exr").is_file() && dir.join("box.partial.png").is_file());
    assert!(!dir.join("box.exr").exists() && !out.exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn sigint_and_sigterm_write_partial_images_and_exit_130() {
    interrupted_by("INT");
    interrupted_by("TERM");
}

/// Issue 26: `--threads` past [`MAX_THREADS`] is refused at once, not a spawning of
/// threads until the machine gives out.
#[test]
fn too_many_threads_are_refused_at_once() {
    for n in ["100000", "18446744073709551615", "1025"] {
        let start = Instant::now();
        let out = Command::new(render_example())
            .args([
                "-D",
                "res=8",
                "-D",
                "spp=1",
                "--threads",
                n,
                "-o",
                "/nonexistent/x.exr",
            ])
            .output()
            .expect("render runs");
        assert_eq!(out.status.code(), Some(2), "{n}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("at most 1024"), "{err}");
        assert!(
            start.elapsed() < Duration::from_secs(5),
            "{:?}",
            start.elapsed()
        );
    }
    assert_eq!(mcrt_render::render::MAX_THREADS, 1024);
    assert!(String::from_utf8_lossy(
        &Command::new(render_example())
            .arg("--help")
            .output()
            .expect("help")
            .stdout
    )
    .contains("at most 1024"));
}

/// Sends `signal` (`INT`, `TERM`) to process `id`.
fn send(signal: &str, id: u32) {
    let sent = Command::new("kill")
        .args([format!("-{signal}"), id.to_string()])
        .status()
        .expect("kill runs");
    assert!(sent.success());
}

/// Waits at most `limit` for `child`; kills it and fails past that.
fn wait_at_most(child: &mut std::process::Child, limit: Duration, what: &str) -> i32 {
    let start = Instant::now();
    loop {
        if let Some(s) = child.try_wait().expect("try_wait") {
            return s
                .code()
                .unwrap_or_else(|| panic!("{what}: ended by a signal: {s:?}"));
        }
        if start.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            panic!("{what}: still running {limit:?} after the signal");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Runs `render scene -o dir/out.exr --threads 1 --max-memory 1T`, sends `signal` once the
/// header line is printed (the render has begun) and `delay` later, and returns the exit
/// status within `limit` and the rest of stdout. The budget admits the 2³² − 1 bootstrap
/// samples of the Metropolis case, which the default budget refuses before rendering;
/// what the bootstrap holds by the time of the signal is small.
fn signal_while_rendering(
    scene: &Path,
    signal: &str,
    delay: Duration,
    limit: Duration,
) -> (i32, String) {
    let out = scene.with_file_name("out.exr");
    let mut child = Command::new(render_example())
        .arg(scene)
        .args(["--threads", "1", "--max-memory", "1T", "-o"])
        .arg(&out)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("render starts");
    let mut stdout = BufReader::new(child.stdout.take().expect("piped stdout"));
    let mut header = String::new();
    stdout.read_line(&mut header).expect("header line");
    std::thread::sleep(delay);
    assert!(child.try_wait().expect("try_wait").is_none(), "ended early");
    send(signal, child.id());
    let what = format!("{} {signal}", scene.display());
    let code = wait_at_most(&mut child, limit, &what);
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stdout, &mut rest).expect("the rest of stdout");
    (code, rest)
}

/// Issue 26: SIGINT and SIGTERM while the scene loads (a 500×500 OBJ grid) end the process
/// at once with status 130 (the handler is installed before loading), writing nothing.
#[test]
fn a_signal_while_loading_exits_130_at_once() {
    let dir = scratch("signal-loading");
    let n = 500;
    let mut obj = String::new();
    for i in 0..n {
        for j in 0..n {
            obj += &format!("v {} {} 0\n", i as f32 / n as f32, j as f32 / n as f32);
        }
    }
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let a = i * n + j + 1;
            obj += &format!("f {a} {} {} {}\n", a + 1, a + n + 1, a + n);
        }
    }
    std::fs::write(dir.join("grid.obj"), obj).expect("mesh written");
    let scene = dir.join("big.xml");
    std::fs::write(
        &scene,
        r#"<scene version="3.0.0"><sensor type="perspective">
        <transform name="to_world"><lookat origin="0.5, 0.5, 3" target="0.5, 0.5, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
        </sensor><shape type="obj"><string name="filename" value="grid.obj"/></shape>
        <emitter type="point"><point name="position" x="0" y="3" z="3"/></emitter></scene>"#,
    )
    .expect("scene written");
    for signal in ["INT", "TERM"] {
        let mut child = Command::new(render_example())
            .arg(&scene)
            .args(["--threads", "1", "-o"])
            .arg(dir.join("out.exr"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("render starts");
        std::thread::sleep(Duration::from_millis(400));
        assert!(
            child.try_wait().expect("try_wait").is_none(),
            "loaded already"
        );
        send(signal, child.id());
        let code = wait_at_most(&mut child, Duration::from_secs(2), signal);
        assert_eq!(code, i32::from(EXIT_INTERRUPTED), "{signal}");
        for f in ["out.exr", "out.png", "out.partial.exr", "out.partial.png"] {
            assert!(!dir.join(f).exists(), "{f}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 26: with `bootstrap_samples` 2³² − 1, Metropolis's bootstrap reads the cancel
/// flag: SIGINT and SIGTERM there write the (empty) partial image and exit 130.
#[test]
fn a_signal_in_the_mlt_bootstrap_exits_130() {
    let dir = scratch("signal-bootstrap");
    let scene = dir.join("mlt.xml");
    std::fs::write(
        &scene,
        r#"<scene version="3.0.0"><integrator type="mlt">
        <integer name="bootstrap_samples" value="4294967295"/><integer name="max_depth" value="4"/>
        </integrator><sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
        </sensor><shape type="sphere"><bsdf type="diffuse"/></shape>
        <emitter type="point"><point name="position" x="0" y="3" z="3"/></emitter></scene>"#,
    )
    .expect("scene written");
    for signal in ["INT", "TERM"] {
        let (code, rest) = signal_while_rendering(
            &scene,
            signal,
            Duration::from_millis(300),
            Duration::from_secs(5),
        );
        assert_eq!(code, i32::from(EXIT_INTERRUPTED), "{signal}: {rest}");
        assert!(rest.contains("interrupted"), "{rest}");
        assert!(dir.join("out.partial.exr").is_file());
        std::fs::remove_file(dir.join("out.partial.exr")).ok();
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 26: in a closed white sphere with `rr_depth` 2³² − 1 and no `max_depth` a path
/// runs for millions of bounces; the path tracer's path ends at its next bounce once the
/// render is cancelled, so SIGINT takes effect at once (it waited for the running path).
#[test]
fn a_signal_stops_an_endless_path_at_once() {
    let dir = scratch("signal-endless");
    let scene = dir.join("white.xml");
    std::fs::write(
        &scene,
        r#"<scene version="3.0.0"><integrator type="path">
        <integer name="max_depth" value="-1"/><integer name="rr_depth" value="4294967295"/>
        </integrator><sensor type="perspective">
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
        </sensor><shape type="sphere"><float name="radius" value="5"/>
        <bsdf type="twosided"><bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf>
        </shape><emitter type="point"><point name="position" x="0" y="1" z="1"/></emitter></scene>"#,
    )
    .expect("scene written");
    let (code, rest) = signal_while_rendering(
        &scene,
        "INT",
        Duration::from_millis(500),
        Duration::from_millis(1500),
    );
    assert_eq!(code, i32::from(EXIT_INTERRUPTED), "{rest}");
    assert!(dir.join("out.partial.exr").is_file());
    std::fs::remove_dir_all(&dir).ok();
}

/// The `merge` program.
fn merge_program() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_merge"))
}

/// Issue 26: a FIFO given to `merge` as a part is refused at once (opening it waited for a
/// writer forever).
#[test]
fn merge_refuses_a_fifo_at_once() {
    let dir = scratch("merge-fifo");
    let fifo = dir.join("part.exr");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let mut child = Command::new(merge_program())
        .arg(dir.join("out.exr"))
        .arg(&fifo)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("merge starts");
    let start = Instant::now();
    while child.try_wait().expect("try_wait").is_none() {
        if start.elapsed() > Duration::from_secs(10) {
            child.kill().ok();
            child.wait().ok();
            panic!("merge waits on a FIFO");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().expect("output");
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("not a regular file") && err.contains("part.exr"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 26: a part whose sums hold NaN is refused with the count of such values and the
/// part's name (it merged into an image with non-finite pixels without a word).
#[test]
fn merge_refuses_a_part_with_nan_sums() {
    let dir = scratch("merge-nan");
    let desc = mcrt_render::cornell_box::cornell_box_with(2, 8, -1);
    let opts = RenderOptions {
        samples: Some("0..2".parse().expect("range")),
        ..RenderOptions::default()
    };
    let r = Renderer::new(&desc, &opts).expect("renderer");
    let mut film = r.render(&|_, _| {}, &AtomicBool::new(false)).film;
    let nan = PixelAccum {
        sum: [f64::NAN; 3],
        sum_sq: [0.0; 3],
        count: 0,
    };
    for i in [3, 17, 40, 41] {
        film.merge(i, &nan).expect("inside the film");
    }
    let part = dir.join("bad.exr");
    mcrt_render::film::write_part(&part, &film, &r.part_info("box")).expect("written");
    let out = Command::new(merge_program())
        .arg(dir.join("out.exr"))
        .arg(&part)
        .output()
        .expect("merge runs");
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.exr") && err.contains("12 values") && err.contains("NaN"),
        "{err}"
    );
    assert!(!dir.join("out.exr").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 26: file names need not be UTF-8: `merge` and `render` take them (`args_os`),
/// and never panic on their arguments.
#[test]
fn non_utf8_arguments_do_not_panic() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;
    let dir = scratch("non-utf8");
    let bad = OsStr::from_bytes(b"caf\xe9.exr");
    // merge: a non-UTF-8 part that does not exist, and a non-UTF-8 output.
    let out = Command::new(merge_program())
        .arg(dir.join(bad))
        .arg(dir.join(OsStr::from_bytes(b"p\xff.exr")))
        .output()
        .expect("merge runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // render: a non-UTF-8 output is written; a non-UTF-8 scene name is read (and missing).
    let out = Command::new(render_example())
        .args(["-D", "res=8", "-D", "spp=1", "-o"])
        .arg(dir.join(bad))
        .output()
        .expect("render runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(dir.join(bad).is_file() && dir.join(OsStr::from_bytes(b"caf\xe9.png")).is_file());
    let out = Command::new(render_example())
        .arg(dir.join(OsStr::from_bytes(b"sc\xe8ne.xml")))
        .output()
        .expect("render runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    // A non-UTF-8 value of another option is a usage error.
    let out = Command::new(render_example())
        .arg("--spp")
        .arg(OsStr::from_bytes(b"4\xff"))
        .output()
        .expect("render runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("not UTF-8") && !err.contains("panicked"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Issue 26: SIGINT and SIGTERM after the render has finished, while the image is written,
/// keep the whole image (not a partial one) and exit 130. The render program's test hook
/// `MCRT_TEST_HOLD_BEFORE_WRITE` holds the finished image until the signal has arrived, so
/// the signal falls in that phase on every run.
#[test]
fn a_signal_while_writing_keeps_the_whole_image_and_exits_130() {
    for signal in ["INT", "TERM"] {
        let dir = scratch(&format!("signal-write-{signal}"));
        let out = dir.join("box.exr");
        let mut child = Command::new(render_example())
            .args(["-D", "spp=4", "-D", "res=16", "--threads", "1", "-o"])
            .arg(&out)
            .env("MCRT_TEST_HOLD_BEFORE_WRITE", "1")
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("render starts");
        let mut stdout = BufReader::new(child.stdout.take().expect("piped stdout"));
        let mut line = String::new();
        while line.trim() != "writing" {
            line.clear();
            let n = stdout.read_line(&mut line).expect("a line of stdout");
            assert!(n > 0, "ended before writing");
        }
        send(signal, child.id());
        let code = wait_at_most(&mut child, Duration::from_secs(30), signal);
        let mut rest = String::new();
        std::io::Read::read_to_string(&mut stdout, &mut rest).expect("the rest of stdout");
        assert_eq!(code, i32::from(EXIT_INTERRUPTED), "{signal}: {rest}");
        assert!(
            rest.contains("interrupted while writing: the image is complete"),
            "{signal}: {rest}"
        );
        let (w, h, px) = read_exr(&out).expect("the whole image is written");
        assert_eq!((w, h), (16, 16), "{signal}");
        // Every pixel has its 4 samples: finite, none NaN as a partial image's unsampled
        // pixels are.
        assert!(px.iter().all(|p| p.is_finite()), "{signal}");
        assert!(!dir.join("box.partial.exr").exists(), "{signal}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
