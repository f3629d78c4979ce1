//! A hostile `.ilmb` cannot make the loader allocate for what it only claims: a table
//! that says it holds four billion entries in a file of a few dozen bytes is refused
//! having allocated a few kilobytes. Its own test binary, because it counts every
//! allocation of the process.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use ilmr_vm::bytecode::{ModuleError, file};
use ilmr_vm::{Module, ModuleBuilder};

struct Counting;

static ALLOCATED: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATED.fetch_add(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATED.fetch_add(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn small_module() -> Vec<u8> {
    let mut b = ModuleBuilder::new();
    let main = b.declare_unit("task", false).expect("unit");
    let blk = b.block(&[]).expect("block");
    b.define_unit(main, &[blk]);
    b.finish().expect("valid").to_bytes()
}

#[test]
fn claimed_lengths_allocate_nothing_for_their_entries() {
    let good = small_module();
    let at = 8 + 4 + 1 + good[12] as usize;
    // postcard's varint of 4,000,000,000.
    let huge = [0x80, 0xd0, 0xac, 0xf3, 0x0e];
    // Each table in turn claims it, after the tables before it, empty.
    for table in 0..6 {
        let mut payload = vec![0u8; table];
        payload.extend_from_slice(&huge);
        payload.extend_from_slice(&[7; 16]);
        let mut bad = good[..at].to_vec();
        bad.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        bad.extend_from_slice(&payload);
        file::seal(&mut bad);
        let before = ALLOCATED.load(Ordering::Relaxed);
        let result = Module::from_bytes(&bad);
        let used = ALLOCATED.load(Ordering::Relaxed) - before;
        assert!(
            matches!(result, Err(ModuleError::Decode(_))),
            "table {table}: {result:?}"
        );
        assert!(used < 64 * 1024, "table {table}: {used} bytes allocated");
    }
}
