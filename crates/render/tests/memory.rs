//! The memory estimate ([`cuticle_render::scene::memory`]) is an upper bound on what a render
//! allocates, and not a loose one: a counting allocator measures the peak of loading and
//! rendering a few scenes whose parts (groom, visibility buffer, shadows, opacity maps) each
//! dominate in turn.

use cuticle_render::{Method, Renderer, Scene, SceneSpec};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

struct Counting;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = NOW.fetch_add(layout.size(), Relaxed) + layout.size();
            PEAK.fetch_max(now, Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        NOW.fetch_sub(layout.size(), Relaxed);
    }
    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, layout, new_size) };
        if !q.is_null() {
            if new_size > layout.size() {
                let now =
                    NOW.fetch_add(new_size - layout.size(), Relaxed) + new_size - layout.size();
                PEAK.fetch_max(now, Relaxed);
            } else {
                NOW.fetch_sub(layout.size() - new_size, Relaxed);
            }
        }
        q
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Peak bytes allocated while loading and rendering `spec` once (tables included).
fn peak_of(spec: &SceneSpec) -> usize {
    PEAK.store(NOW.load(Relaxed), Relaxed);
    let start = NOW.load(Relaxed);
    let renderer = Renderer::new();
    let scene = Scene::load(spec.clone(), None).unwrap();
    let (image, _, _) = renderer.render(&scene);
    assert_eq!(image.pixels.len(), spec.width * spec.height);
    PEAK.load(Relaxed) - start
}

#[test]
fn the_estimate_bounds_the_peak_within_a_small_factor() {
    let threads = rayon::current_num_threads();
    let cases: [fn(&mut SceneSpec); 4] = [
        |s| (s.strands, s.width, s.height) = (400, 64, 48),
        |s| (s.strands, s.width, s.height, s.supersampling) = (400, 900, 700, 6),
        |s| (s.strands, s.width, s.height, s.lights) = (20_000, 96, 64, 8),
        |s| {
            (s.strands, s.width, s.height) = (400, 160, 120);
            (s.method, s.brute_grid, s.shadows.resolution) = (Method::Brute, 3, 1024);
        },
    ];
    for spoil in cases {
        let mut spec = SceneSpec {
            multiple: false,
            ..SceneSpec::default()
        };
        spoil(&mut spec);
        let peak = peak_of(&spec);
        let need = spec.memory_need(None, threads).total() as usize;
        eprintln!(
            "{}x{} ss {} strands {} {:?}: peak {:.1} MB, estimate {:.1} MB",
            spec.width,
            spec.height,
            spec.supersampling,
            spec.strands,
            spec.method,
            peak as f64 / 1e6,
            need as f64 / 1e6
        );
        assert!(need >= peak, "estimate {need} below the peak {peak}");
        assert!(
            need <= 4 * peak.max(64 << 20),
            "estimate {need} far above the peak {peak}"
        );
    }
}
