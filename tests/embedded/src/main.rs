//! The embedded check: the 3-link planar chain in `f32` stepped with the
//! runtime's RK4 on a Cortex-M4F (QEMU's mps2-an386), its final state and
//! the stack one `derivatives()` call uses printed over semihosting. The
//! host computes the same run (`cargo run -p autosim-no-std-check
//! --example swing_f32`); `.ci/run` compares the two.
#![no_std]
#![no_main]

use autosim_no_std_check::{ChainPlanar3F32, swing_f32};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};

/// A word that marks unused stack.
const PAINT: u32 = 0xDEAD_BEEF;
/// How much stack below the current frame is painted.
const PAINTED_WORDS: usize = 4096;

#[entry]
fn main() -> ! {
    match swing_f32() {
        Ok(x) => hprintln!(
            "state: {:e} {:e} {:e} {:e} {:e} {:e}",
            x[0],
            x[1],
            x[2],
            x[3],
            x[4],
            x[5]
        ),
        Err(_) => hprintln!("error"),
    }
    hprintln!("stack of one derivatives() call: {} bytes", derivatives_stack());
    debug::exit(debug::EXIT_SUCCESS);
    loop {}
}

/// Paints the stack below this frame, calls `derivatives` once, and counts
/// the painted words it overwrote.
#[inline(never)]
fn derivatives_stack() -> usize {
    let sp = cortex_m::register::msp::read() as usize;
    let bottom = sp - 256 - PAINTED_WORDS * 4;
    // SAFETY: the region lies below the live stack, inside RAM (4 MiB on
    // this machine), and nothing else uses it; written and read as words.
    unsafe {
        for k in 0..PAINTED_WORDS {
            core::ptr::write_volatile((bottom + 4 * k) as *mut u32, PAINT);
        }
    }
    call_derivatives();
    let mut untouched = 0;
    // SAFETY: as above.
    unsafe {
        while untouched < PAINTED_WORDS
            && core::ptr::read_volatile((bottom + 4 * untouched) as *const u32) == PAINT
        {
            untouched += 1;
        }
    }
    (PAINTED_WORDS - untouched) * 4
}

#[inline(never)]
fn call_derivatives() {
    use autosim_no_std_check::ChainPlanar3F32 as M;
    let mut model: M = ChainPlanar3F32::new();
    let x = core::hint::black_box([0.3f32, -0.2, 0.1, 0.0, 0.0, 0.0]);
    let mut dx = [0.0f32; 6];
    let _ = core::hint::black_box(autosim_no_std_check::derivatives_f32(&mut model, &x, &mut dx));
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    debug::exit(debug::EXIT_FAILURE);
    loop {}
}
