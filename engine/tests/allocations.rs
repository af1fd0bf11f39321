//! What must not allocate, counted with a counting global allocator (this test binary only):
//! - an IPO cycle inside a block, for every transformation family: thousands of real-time
//!   sessions step 250 times a second each, and memory must stay flat;
//! - the snapshot refresh of a real-time session (20 times a second), once the kept snapshot
//!   has the running program's shape (axes, G code names, the longest block text so far).

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

/// Allocations of `cycles` IPO cycles in the middle of the long block on `line` of `program`:
/// after `warm_up` cycles, when block preparation has reached the program end and only the
/// interpolation of that block (with its transformation) runs.
fn allocations_inside_a_block(preset: &str, program: &str, line: u32) -> u64 {
    let mut ch = Channel::from_preset(preset, "").unwrap_or_else(|e| panic!("{preset}: {e}"));
    ch.run_program(program).unwrap_or_else(|e| panic!("{preset}: {e:?}"));
    let current_line = |ch: &Channel| ch.snapshot().block.map(|b| b.line);
    let mut warm_up = 0;
    while current_line(&ch) != Some(line) || warm_up < 2_000 {
        ch.step();
        warm_up += 1;
        assert!(warm_up < 200_000 && ch.is_busy(), "{preset}: never ran line {line}: {:?}", ch.snapshot().alarms);
    }
    let before = allocations();
    for _ in 0..5_000 {
        ch.step();
    }
    let during = allocations() - before;
    assert!(ch.is_busy(), "{preset}: the block lasts longer than the count");
    assert_eq!(current_line(&ch), Some(line), "{preset}: still in the same block");
    during
}

#[test]
fn an_ipo_cycle_inside_a_block_allocates_nothing() {
    // Each long block is slow enough (F20..F100) to last well over 7,000 cycles of 4 ms.
    let cases = [
        ("mill-3axis", "G54 T1 D1 F100\nG0 X0 Y0 Z1\nG1 X300 Y40 Z-2\nM30\n", 3),
        ("mill-3axis", "T1 D1 F100\nG0 X50 Y0 Z0\nG3 X50 Y0 Z-5 I-50 J0\nM30\n", 3),
        ("transmit-example", "T1 D1 G17\nG0 X20 Z10\nTRANSMIT\nG1 F20 X10 Y-10\nY10\nM30\n", 5),
        ("tracyl-xyzc", "G0 X20 Y0 Z0\nTRACYL(40)\nG1 F100 Y100 Z-10\nM30\n", 3),
        ("traang-grinder", "G0 X0 Z0\nTRAANG\nG1 F20 X10 Z-50\nM30\n", 3),
        ("mill5-head-ca", "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nG1 F50 X50 A30 C20\nM30\n", 4),
        ("mill5-table-ac", "T1 D1\nG0 X0 Y0 Z50\nTRAORI\nORIWKS ORIVECT\nG1 F50 X40 A3=0 B3=1 C3=1\nM30\n", 5),
    ];
    for (preset, program, line) in cases {
        assert_eq!(
            allocations_inside_a_block(preset, program, line),
            0,
            "{preset}: allocations in 5,000 cycles of line {line}"
        );
    }
}
