//! The native half of the Python package `holey` (`holey._holey`).
//!
//! The Python half (`python/holey/__init__.py`) turns whatever array-like
//! the caller passes into contiguous little-endian buffers (`float64`
//! positions, `uint32` indices) after checking their shapes, and turns
//! the buffers this module returns back into numpy arrays. Passing bytes
//! rather than numpy objects keeps the module on the stable ABI (one
//! `abi3` wheel for every Python from 3.9), at the price of one copy each
//! way, which is measured against the engine's time in BENCHMARKS.md.
//!
//! Every function here only calls the library (`holey`): the policy lives
//! there. The GIL is released around each engine call, and `threads`
//! runs it on a local rayon pool of that many threads.

use pyo3::prelude::*;

mod arrays;
mod engine;
mod errors;
mod files;
mod kernel;
mod toolbox;

/// The module `holey._holey`.
#[pymodule]
fn _holey(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // Panics the engine catches itself (spade's splitting insertion) are
    // not printed into the interpreter's stderr.
    holey::topo::hide_caught_triangulation_panics();
    let py = m.py();
    m.add("HoleyError", py.get_type::<errors::HoleyError>())?;
    m.add_function(wrap_pyfunction!(engine::boolean, m)?)?;
    m.add_function(wrap_pyfunction!(engine::topology_change, m)?)?;
    m.add_function(wrap_pyfunction!(engine::self_intersections, m)?)?;
    m.add_function(wrap_pyfunction!(engine::resolve, m)?)?;
    m.add_function(wrap_pyfunction!(engine::info, m)?)?;
    m.add_function(wrap_pyfunction!(engine::sculpt, m)?)?;
    m.add_function(wrap_pyfunction!(files::read, m)?)?;
    m.add_function(wrap_pyfunction!(files::write, m)?)?;
    m.add_class::<kernel::Mesh>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
