//! The memory budget: one figure, in bytes, that every size read from a file or an argument
//! is checked against **before** the memory it implies is allocated (mesh files, texture
//! images, the film, the state of Metropolis light transport, the image `merge` adds parts
//! into). See `docs/renderer.md`, "Memory budget".
//!
//! The budget is a property of the process (the programs set it once from `--max-memory`,
//! a library user with [`set_max_memory`]); it defaults to [`DEFAULT_MAX_MEMORY`]. A check
//! that fails says what would have been needed and how to raise the limit.

use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

/// The default budget: 8 GiB. A fixed figure rather than a fraction of the machine's
/// memory, so that a scene that loads on one machine loads (or is refused) alike on
/// another; it is far above what ordinary scenes need (the test scenes need megabytes) and
/// below the memory of a common 16 GB workstation, so a hostile file is refused instead of
/// taking the machine down.
pub const DEFAULT_MAX_MEMORY: u64 = 8 << 30;

static MAX_MEMORY: AtomicU64 = AtomicU64::new(DEFAULT_MAX_MEMORY);

/// Sets the process's memory budget in bytes.
pub fn set_max_memory(bytes: u64) {
    MAX_MEMORY.store(bytes, Ordering::Relaxed);
}

/// The process's memory budget in bytes.
pub fn max_memory() -> u64 {
    MAX_MEMORY.load(Ordering::Relaxed)
}

thread_local! {
    /// Bytes this thread's caller holds already for the same scene (the meshes built
    /// before the one being read): every check inside [`with_held`] sees only the rest of
    /// the budget.
    static HELD: Cell<u64> = const { Cell::new(0) };
}

/// Runs `f` with `bytes` counted as held already, so that [`check`], [`available`] and
/// [`over_budget`] inside it weigh each new size against what remains of the budget (the
/// geometry sums its meshes this way, each file's reader unchanged).
pub fn with_held<R>(bytes: u64, f: impl FnOnce() -> R) -> R {
    let before = HELD.with(|h| h.replace(bytes));
    let r = f();
    HELD.with(|h| h.set(before));
    r
}

/// Bytes counted as held by [`with_held`] on this thread (0 outside it).
pub fn held() -> u64 {
    HELD.with(Cell::get)
}

/// What remains of the budget for new allocations: [`max_memory`] less [`held`].
pub fn available() -> u64 {
    max_memory().saturating_sub(held())
}

/// Parses a size such as `4G`, `512M`, `1.5GiB`, `64k` or `100000` (bytes); the suffixes
/// K, M, G, T (optionally followed by `iB` or `B`) are powers of 1024.
///
/// ```
/// use mcrt_render::memory::parse_size;
/// assert_eq!(parse_size("4G"), Ok(4 << 30));
/// assert_eq!(parse_size("1.5GiB"), Ok(3 << 29));
/// assert_eq!(parse_size("100000"), Ok(100000));
/// assert!(parse_size("lots").is_err());
/// ```
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let lower = t.to_ascii_lowercase();
    let body = lower
        .strip_suffix("ib")
        .or_else(|| lower.strip_suffix('b'))
        .unwrap_or(&lower);
    let (num, unit) = match body.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => (&body[..i], c),
        _ => (body, ' '),
    };
    let scale: u64 = match unit {
        ' ' => 1,
        'k' => 1 << 10,
        'm' => 1 << 20,
        'g' => 1 << 30,
        't' => 1 << 40,
        _ => return Err(format!("\"{s}\": unknown unit (use K, M, G or T)")),
    };
    let v: f64 = num
        .parse()
        .map_err(|_| format!("\"{s}\" is not a size such as 4G, 512M or 100000"))?;
    let bytes = v * scale as f64;
    if !(bytes >= 1.0 && bytes < 2f64.powi(63)) {
        return Err(format!(
            "\"{s}\": a size must be at least 1 byte and below 8 EiB"
        ));
    }
    Ok(bytes as u64)
}

/// A size for messages: `1.50 GiB (1610612736 bytes)`.
pub fn format_size(bytes: u64) -> String {
    let units = [("TiB", 40), ("GiB", 30), ("MiB", 20), ("KiB", 10)];
    for (name, shift) in units {
        if bytes >= 1 << shift {
            let v = bytes as f64 / (1u64 << shift) as f64;
            return format!("{v:.2} {name} ({bytes} bytes)");
        }
    }
    format!("{bytes} bytes")
}

/// The `--max-memory` value that would admit `bytes`: rounded up to a whole MiB or GiB.
fn suggestion(bytes: u64) -> String {
    if bytes >= 1 << 30 {
        format!("{}G", bytes.div_ceil(1 << 30))
    } else {
        format!("{}M", bytes.div_ceil(1 << 20).max(1))
    }
}

/// The message of a refusal: `what` would need `bytes`, more than the budget (or than what
/// [`held`] leaves of it).
pub fn over_budget(what: &str, bytes: u64) -> String {
    let held = held();
    if held == 0 {
        return format!(
            "{what} would need {}, more than the memory budget of {}; raise the limit with \
             --max-memory {} (or more) if the machine has the memory",
            format_size(bytes),
            format_size(max_memory()),
            suggestion(bytes)
        );
    }
    let total = bytes.saturating_add(held);
    format!(
        "{what} would need {}, beside {} that the scene holds already: {} in all, more than \
         the memory budget of {}; raise the limit with --max-memory {} (or more) if the \
         machine has the memory",
        format_size(bytes),
        format_size(held),
        format_size(total),
        format_size(max_memory()),
        suggestion(total)
    )
}

/// Checks that `bytes` (what `what` would need) fit in what remains of the budget
/// ([`available`]).
pub fn check(what: &str, bytes: u64) -> Result<(), String> {
    if bytes > available() {
        return Err(over_budget(what, bytes));
    }
    Ok(())
}

/// `a × b` bytes, saturating (a size from a file may be absurd).
pub fn bytes(count: u64, per_item: usize) -> u64 {
    count.saturating_mul(per_item as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_bytes_leave_the_rest_of_the_budget() {
        let budget = max_memory();
        assert_eq!(held(), 0);
        with_held(budget - 100, || {
            assert_eq!(available(), 100);
            assert!(check("a mesh", 100).is_ok());
            let e = check("a mesh", 101).expect_err("past what is left");
            assert!(e.contains("beside"), "{e}");
            assert!(e.contains("a mesh would need 101 bytes"), "{e}");
        });
        assert_eq!(held(), 0);
        assert!(check("a mesh", 101).is_ok());
    }

    #[test]
    fn sizes_parse_and_messages_say_how_to_raise() {
        assert_eq!(parse_size("4G"), Ok(4 << 30));
        assert_eq!(parse_size("512m"), Ok(512 << 20));
        assert_eq!(parse_size("64KiB"), Ok(64 << 10));
        assert_eq!(parse_size("2T"), Ok(2 << 40));
        assert_eq!(parse_size("4096B"), Ok(4096));
        assert!(parse_size("0").is_err());
        assert!(parse_size("-3G").is_err());
        assert!(parse_size("4X").is_err());
        assert!(parse_size("99999999T").is_err());
        let m = over_budget("the image", 3 << 30);
        assert!(m.contains("3.00 GiB (3221225472 bytes)"), "{m}");
        assert!(m.contains("--max-memory 3G"), "{m}");
        assert_eq!(format_size(100), "100 bytes");
    }
}
