//! Test support shared by holey's crates: a small seeded PRNG, so seeded
//! property tests give the same sequence on every platform and version,
//! small meshes as plain arrays ([`meshes`]), oracles on triangle index
//! lists ([`oracles`]), exact reference arithmetic ([`exact`]: big
//! integers and polynomials in ε), and the location of the shared
//! real-mesh data.

use std::path::PathBuf;

pub mod exact;
pub mod meshes;
pub mod oracles;

pub use meshes::{
    AXES, grid_triangles, lattice_cubes, menger_cells, octahedron, quad_torus, tetrahedron,
    unit_cube, uv_sphere, uv_spheres,
};
pub use oracles::{Groups, boundary, components, edge_degrees, pieces};

/// SplitMix64 (Steele, Lea & Flood 2014): tiny, fast, and fully
/// determined by its seed.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (((self.next_u64() >> 11) as u128 * n as u128) >> 53) as usize
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in the cube [lo, hi)³, drawn x, then y, then z (so it gives
    /// the numbers three calls of [`Rng::range`] would).
    pub fn point(&mut self, lo: f64, hi: f64) -> [f64; 3] {
        self.in_box([lo; 3], [hi; 3])
    }

    /// Uniform in the axis-aligned box from `lo` to `hi` (each coordinate
    /// in [lo, hi)), drawn x, then y, then z: the numbers three calls of
    /// [`Rng::range`] would give. Sampling a box this way is how the tests
    /// estimate volumes (the share of points inside) and check
    /// classifications at random points.
    pub fn in_box(&mut self, lo: [f64; 3], hi: [f64; 3]) -> [f64; 3] {
        let x = self.range(lo[0], hi[0]);
        let y = self.range(lo[1], hi[1]);
        let z = self.range(lo[2], hi[2]);
        [x, y, z]
    }

    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// A uniformly chosen element.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// `../shared/data/<sub>` relative to the repository, or the folder the
/// environment variable `var` names; `None` when it is absent.
fn shared_dir(sub: &str, var: &str) -> Option<PathBuf> {
    if let Ok(dir) = std::env::var(var) {
        let p = PathBuf::from(dir);
        return p.is_dir().then_some(p);
    }
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data")
        .join(sub);
    root.is_dir().then(|| root.canonicalize().unwrap_or(root))
}

/// The shared folder of real meshes made by others (`../shared/data/meshes`
/// relative to the repository, or `HOLEY_SHARED_MESHES`), or `None` when
/// it is absent. Tests that read it must say so and skip visibly when this
/// is `None`.
pub fn shared_meshes() -> Option<PathBuf> {
    shared_dir("meshes", "HOLEY_SHARED_MESHES")
}

/// The shared Boolean corpus (`../shared/data/corpus`: the EMBER pairs and
/// the overlapping shells, or `HOLEY_SHARED_CORPUS`), or `None` when it is
/// absent, after a visible SKIP line naming `test`.
pub fn shared_corpus_or_skip(test: &str) -> Option<PathBuf> {
    let dir = shared_dir("corpus", "HOLEY_SHARED_CORPUS");
    if dir.is_none() {
        eprintln!(
            "SKIP {test}: ../shared/data/corpus is absent (set HOLEY_SHARED_CORPUS to point at it)"
        );
    }
    dir
}

/// Returns the shared mesh folder, or prints a visible SKIP line naming the
/// test and returns `None`.
pub fn shared_meshes_or_skip(test: &str) -> Option<PathBuf> {
    let dir = shared_meshes();
    if dir.is_none() {
        eprintln!(
            "SKIP {test}: ../shared/data/meshes is absent (set HOLEY_SHARED_MESHES to point at it)"
        );
    }
    dir
}

/// The folder in `$dir`, an `Option`, or a return from the enclosing
/// test when it is `None` (the two macros below, after their SKIP line).
#[doc(hidden)]
#[macro_export]
macro_rules! __dir_or_return {
    ($dir:expr) => {
        match $dir {
            Some(dir) => dir,
            None => return,
        }
    };
}

/// In a test: the shared mesh folder, or — after the SKIP line of
/// [`shared_meshes_or_skip`] naming `test` — a return from the test, which
/// has nothing to check without it.
#[macro_export]
macro_rules! shared_meshes_or_return {
    ($test:expr) => {
        $crate::__dir_or_return!($crate::shared_meshes_or_skip($test))
    };
}

/// In a test: the shared Boolean corpus, or — after the SKIP line of
/// [`shared_corpus_or_skip`] naming `test` — a return from the test.
#[macro_export]
macro_rules! shared_corpus_or_return {
    ($test:expr) => {
        $crate::__dir_or_return!($crate::shared_corpus_or_skip($test))
    };
}
