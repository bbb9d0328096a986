//! The traversal stack of the wide BVHs (`traverse.rs`, `traverse8.rs`): entries pack a
//! child code and its entry distance's bits into one `u64`, so zeroing a fresh array is a
//! few vector stores; a fixed array on the call stack sized for the tree (the two smaller
//! sizes), a per-thread array borrowed for the query (the largest size: a fresh one would be
//! zeroed with a `memset` per query), or a per-thread buffer for trees too deep for the
//! largest array ([`with_stack`]).

/// A stack entry: child code in the low half, entry distance's bits in the high half.
#[inline(always)]
pub(super) fn entry(code: u32, t: f32) -> u64 {
    u64::from(code) | u64::from(t.to_bits()) << 32
}

/// A traversal stack of packed entries ([`entry`]).
pub(super) trait Stack {
    fn push(&mut self, e: u64);
    fn pop(&mut self) -> Option<u64>;
}

impl Stack for Vec<u64> {
    #[inline(always)]
    fn push(&mut self, e: u64) {
        Vec::push(self, e);
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<u64> {
        Vec::pop(self)
    }
}

/// A fixed-capacity stack over an array it owns (`[u64; N]`, on the call stack: an
/// [`ArrayStack`]) or borrows (`&mut [u64; N]`, a per-thread array reused by every query: a
/// [`BorrowedStack`]), capacity checked against the tree depth before use. The entries below
/// `len` are the ones pushed; what lies above is never read, so a borrowed array is not
/// zeroed per query.
pub(super) struct FixedStack<A> {
    items: A,
    len: usize,
}

/// A [`FixedStack`] on the call stack.
pub(super) type ArrayStack<const N: usize> = FixedStack<[u64; N]>;

/// A [`FixedStack`] over a borrowed array.
pub(super) type BorrowedStack<'a, const N: usize> = FixedStack<&'a mut [u64; N]>;

impl<const N: usize> FixedStack<[u64; N]> {
    #[inline(always)]
    pub(super) fn new() -> Self {
        Self {
            items: [0; N],
            len: 0,
        }
    }
}

impl<'a, const N: usize> FixedStack<&'a mut [u64; N]> {
    #[inline(always)]
    pub(super) fn new(items: &'a mut [u64; N]) -> Self {
        Self { items, len: 0 }
    }
}

impl<A: AsMut<[u64]>> Stack for FixedStack<A> {
    #[inline(always)]
    fn push(&mut self, e: u64) {
        let items = self.items.as_mut();
        debug_assert!(self.len < items.len());
        if let Some(slot) = items.get_mut(self.len) {
            *slot = e;
            self.len += 1;
        }
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<u64> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items.as_mut()[self.len])
    }
}

/// Pops the nearest pending child that may still hold a hit within `t_max`: its code, or
/// `None` when the stack runs out.
#[inline(always)]
pub(super) fn pop_within(stack: &mut impl Stack, t_max: f32) -> Option<u32> {
    loop {
        let e = stack.pop()?;
        if f32::from_bits((e >> 32) as u32) <= t_max {
            return Some(e as u32);
        }
    }
}

/// `with_stack!(levels, [TINY, SMALL, LARGE], |stack| walk)`: evaluates `walk` with `stack`
/// a fresh traversal stack for a tree that pushes at most `levels` entries: the smallest of
/// the sizes `TINY`, `SMALL` and `LARGE` (constants) that holds them, else a per-thread
/// growable buffer (one per place the macro is used, cleared first). `TINY` and `SMALL` are fresh
/// [`ArrayStack`]s; `LARGE` is a [`BorrowedStack`] over a per-thread array, allocated once
/// per thread (zeroing a fresh one costs a `memset` per query; a query made while another
/// walks finds the cell empty and allocates its own). A macro rather than a function taking
/// a closure, so that the walk is inlined for each stack type.
macro_rules! with_stack {
    ($levels:expr, [$tiny:ident, $small:ident, $large:ident], |$stack:ident| $walk:expr) => {{
        thread_local! {
            static HEAP: std::cell::Cell<Vec<u64>> = const { std::cell::Cell::new(Vec::new()) };
            static LARGE_ITEMS: std::cell::Cell<Option<Box<[u64; $large]>>> =
                const { std::cell::Cell::new(None) };
        }
        let levels = $levels;
        if levels <= $tiny {
            let $stack = &mut $crate::accel::stack::ArrayStack::<$tiny>::new();
            $walk
        } else if levels <= $small {
            let $stack = &mut $crate::accel::stack::ArrayStack::<$small>::new();
            $walk
        } else if levels <= $large {
            // Taken out of the cell for the walk (a cheap move of the box, so the walk is not
            // wrapped in a closure the compiler may leave out of line), put back after it.
            let mut items = LARGE_ITEMS.take().unwrap_or_else(|| Box::new([0; $large]));
            let found = {
                let $stack = &mut $crate::accel::stack::BorrowedStack::new(&mut *items);
                $walk
            };
            // `with` and `Cell::set`, not `LocalKey::set`, which is left out of line.
            LARGE_ITEMS.with(|cell| cell.set(Some(items)));
            found
        } else {
            // Taken out of the cell for the walk (a query made while another walks finds it
            // empty and grows its own, where a borrow would panic); the walk stays in the
            // closure, out of line, as the rare case it is.
            HEAP.with(|cell| {
                let mut heap = cell.take();
                heap.clear();
                let found = {
                    let $stack = &mut heap;
                    $walk
                };
                cell.set(heap);
                found
            })
        }
    }};
}
pub(super) use with_stack;

#[cfg(test)]
mod tests {
    use super::*;

    const TINY: usize = 2;
    const SMALL: usize = 4;
    const LARGE: usize = 8;

    /// Pushes `values` on a stack for `levels`, optionally runs the same query nested inside
    /// (which finds the per-thread array of the `LARGE` size taken), pops the stack empty and
    /// returns the sum of what was popped; `None` if the stack was not empty at the start.
    fn sum_through_stack(levels: usize, values: &[u64], nested: bool) -> Option<u64> {
        with_stack!(levels, [TINY, SMALL, LARGE], |stack| {
            if stack.pop().is_some() {
                return None;
            }
            for &v in values {
                stack.push(v);
            }
            let mut sum = if nested {
                sum_through_stack(levels, values, false)?
            } else {
                0
            };
            while let Some(e) = stack.pop() {
                sum += e;
            }
            Some(sum)
        })
    }

    #[test]
    fn every_size_starts_empty_and_pops_what_was_pushed() {
        for (levels, n) in [(1, 2), (3, 4), (5, 8), (8, 8), (20, 20)] {
            let values: Vec<u64> = (1..=n).map(|v| v * 10).collect();
            let want: u64 = values.iter().sum();
            // Twice: the second query reuses the per-thread array the first filled.
            for _ in 0..2 {
                assert_eq!(sum_through_stack(levels, &values, false), Some(want));
            }
            assert_eq!(sum_through_stack(levels, &values, true), Some(2 * want));
        }
    }

    #[test]
    fn a_borrowed_stack_ignores_what_lies_above_its_length() {
        let mut items = [7u64; 4];
        let mut stack = BorrowedStack::new(&mut items);
        assert_eq!(stack.pop(), None);
        stack.push(1);
        stack.push(2);
        assert_eq!(stack.pop(), Some(2));
        assert_eq!(stack.pop(), Some(1));
        assert_eq!(stack.pop(), None);
    }
}
