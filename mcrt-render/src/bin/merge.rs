//! Merges the parts of a render into the image a single render would have given.
//!
//! ```text
//! cargo run --release --bin merge -- [--variance] [--max-memory SIZE] OUT.exr|OUT.png PARTS.exr...
//! ```
//!
//! `--max-memory` (e.g. `4G`, default 8G) is the memory budget: a part whose image would
//! need more to merge is refused before anything is allocated (docs/renderer.md).
//!
//! The parts are written by `render --samples START..END` and/or `--crop x0,y0,x1,y1` (see
//! `docs/distributed.md`). Their per-pixel sums and sample counts are added in f64, so the
//! result equals a single render's up to the final rounding to f32, and it is written as the
//! render example writes a whole image: OUT.exr and OUT.png beside it (and
//! OUT-variance.exr with `--variance`), atomically. Parts of different renders (scene,
//! options, seed, samples per pixel or size), parts that hold the same samples of a pixel,
//! parts that leave samples out, and interrupted parts are refused, with the files and
//! pixels concerned; nothing is written then. So are parts whose sums hold NaN or infinite
//! values (with their count and the first pixel), and parts that are not regular files (a
//! FIFO would block). File names need not be UTF-8. Exit status 0 on success, 1 on a
//! refusal, 2 on a usage error.

use mcrt_render::film::{merge_parts, read_part, OutputPlan};
use std::ffi::OsString;
use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "usage: merge [--variance] [--max-memory SIZE] OUT.exr|OUT.png PARTS.exr...";

fn run(out: PathBuf, parts: Vec<PathBuf>, variance: bool) -> Result<(), String> {
    let name = out
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "merged".into());
    let plan = OutputPlan::new(Some(&out), &name, None, variance).map_err(|e| e.to_string())?;
    plan.check_not_inputs(&parts).map_err(|e| e.to_string())?;
    plan.check_writable().map_err(|e| e.to_string())?;
    let read = parts
        .iter()
        .map(|p| read_part(p))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())?;
    let film = merge_parts(&read).map_err(|e| e.to_string())?;
    let info = &read[0].info;
    println!(
        "{}: {} parts, {}×{}, {} spp, seed {}, scene identity {:016x}",
        info.scene,
        read.len(),
        info.width,
        info.height,
        info.spp,
        info.seed,
        info.identity
    );
    let written = plan.write(&film, false).map_err(|e| e.to_string())?;
    let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    println!("wrote {}", names.join(", "));
    Ok(())
}

fn main() -> ExitCode {
    // `args_os`: a file name need not be UTF-8 (`args` would panic on it).
    let mut args: Vec<OsString> = std::env::args_os().skip(1).collect();
    let is = |a: &OsString, s: &str| a.as_os_str() == s;
    if args.iter().any(|a| is(a, "--help") || is(a, "-h")) {
        println!("{USAGE}\n\nAdds the parts written by render --samples/--crop into one image.");
        return ExitCode::SUCCESS;
    }
    let variance = args.iter().any(|a| is(a, "--variance"));
    args.retain(|a| !is(a, "--variance"));
    if let Some(i) = args.iter().position(|a| is(a, "--max-memory")) {
        let size = args.get(i + 1).map(|v| match v.to_str() {
            Some(v) => mcrt_render::memory::parse_size(v),
            None => Err(format!("{}: not a size", v.to_string_lossy())),
        });
        match size {
            Some(Ok(bytes)) => mcrt_render::memory::set_max_memory(bytes),
            Some(Err(e)) => {
                eprintln!("error: --max-memory {e}\n{USAGE}");
                return ExitCode::from(2);
            }
            None => {
                eprintln!("error: --max-memory needs a size such as 4G\n{USAGE}");
                return ExitCode::from(2);
            }
        }
        args.drain(i..i + 2);
    }
    if let Some(bad) = args
        .iter()
        .find(|a| a.as_encoded_bytes().starts_with(b"--"))
    {
        eprintln!("error: unknown option {}\n{USAGE}", bad.to_string_lossy());
        return ExitCode::from(2);
    }
    if args.len() < 2 {
        eprintln!("error: an output and at least one part are needed\n{USAGE}");
        return ExitCode::from(2);
    }
    let out = PathBuf::from(&args[0]);
    let parts = args[1..].iter().map(PathBuf::from).collect();
    match run(out, parts, variance) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
