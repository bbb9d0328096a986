//! The traversal stack of the wide BVHs (`traverse.rs`, `traverse8.rs`): entries pack a
//! child code and its entry distance's bits into one `u64`, so zeroing a fresh array is a
//! few vector stores; a fixed array on the call stack sized for the tree, or a per-thread
//! buffer for trees too deep for the largest array ([`with_stack`]).

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

/// A fixed-capacity stack on the call stack (capacity checked against the tree depth
/// before use).
pub(super) struct ArrayStack<const N: usize> {
    items: [u64; N],
    len: usize,
}

impl<const N: usize> ArrayStack<N> {
    #[inline(always)]
    pub(super) fn new() -> Self {
        Self {
            items: [0; N],
            len: 0,
        }
    }
}

impl<const N: usize> Stack for ArrayStack<N> {
    #[inline(always)]
    fn push(&mut self, e: u64) {
        debug_assert!(self.len < N);
        if let Some(slot) = self.items.get_mut(self.len) {
            *slot = e;
            self.len += 1;
        }
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<u64> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
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
/// the [`ArrayStack`] sizes `TINY`, `SMALL` and `LARGE` (constants) that holds them, else a
/// per-thread buffer (one per place the macro is used, cleared first). A macro rather than a
/// function taking a closure, so that the walk is inlined for each stack type.
macro_rules! with_stack {
    ($levels:expr, [$tiny:ident, $small:ident, $large:ident], |$stack:ident| $walk:expr) => {{
        thread_local! {
            static HEAP: std::cell::RefCell<Vec<u64>> =
                std::cell::RefCell::new(Vec::with_capacity(256));
        }
        let levels = $levels;
        if levels <= $tiny {
            let $stack = &mut $crate::accel::stack::ArrayStack::<$tiny>::new();
            $walk
        } else if levels <= $small {
            let $stack = &mut $crate::accel::stack::ArrayStack::<$small>::new();
            $walk
        } else if levels <= $large {
            let $stack = &mut $crate::accel::stack::ArrayStack::<$large>::new();
            $walk
        } else {
            HEAP.with_borrow_mut(|$stack| {
                $stack.clear();
                $walk
            })
        }
    }};
}
pub(super) use with_stack;
