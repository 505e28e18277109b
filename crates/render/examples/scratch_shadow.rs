use cuticle_render::{Renderer, Scene, SceneSpec, Timings};
fn main() {
    let scene = Scene::load(SceneSpec::default(), None).unwrap();
    let r = Renderer::new();
    let mut t = Timings::default();
    let p = r.prepare(&scene, &mut t);
    let n = p.shadow.len() as f64;
    for th in [1e-6f32, 1e-4, 1e-3, 1e-2, 0.1] {
        let c = p.shadow.iter().filter(|&&s| s < th).count() as f64;
        println!("t < {th}: {:.1} %", 100.0 * c / n);
    }
}
