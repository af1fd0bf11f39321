//! A real-time session refreshes its snapshot 20 times a second: once the kept snapshot has
//! the running program's shape (axes, G code names, the longest block text so far), a refresh
//! must not allocate. Counted with a counting global allocator (this test binary only).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use nctwin_engine::Channel;

struct Counting;

thread_local! {
    /// Allocations of this thread (tests run on threads of their own).
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

// SAFETY: forwards every call to the system allocator unchanged; only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        // SAFETY: the caller's contract is passed on.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

#[test]
fn refreshing_a_running_program_allocates_nothing() {
    // Pockets of G1/G3 blocks (the motion mode changes every block), lines of one length.
    let mut program = String::from("G54 G17 T1 D1 F3000\nG0 X10 Y0 Z1\nG1 Z-1\n");
    for i in 0..200 {
        let r = 10 + i % 5;
        program += &format!("G1 X{r}.000 Y0.000\nG3 X-{r}.000 Y0.000 I-{r}.000 J0\nG3 X{r}.000 Y0.000 I{r}.000 J0\n");
    }
    program += "M30\n";
    let mut ch = Channel::from_preset("mill-3axis", "").expect("preset");
    ch.run_program(&program).expect("program");
    let mut kept = ch.snapshot();
    // Warm-up: the first blocks grow the block text to its longest.
    for _ in 0..50 {
        for _ in 0..12 {
            ch.step();
        }
        ch.refresh_snapshot(&mut kept);
    }
    let mut during_refresh = 0;
    let first = kept.block.as_ref().map(|b| b.line);
    for _ in 0..1_000 {
        for _ in 0..12 {
            ch.step();
        }
        let before = allocations();
        ch.refresh_snapshot(&mut kept);
        during_refresh += allocations() - before;
    }
    assert!(ch.is_busy(), "the program still runs");
    assert_ne!(kept.block.as_ref().map(|b| b.line), first, "blocks changed meanwhile");
    assert_eq!(kept, ch.snapshot());
    assert_eq!(during_refresh, 0, "allocations in 1,000 refreshes");
}
