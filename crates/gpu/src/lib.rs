//! The SRBF hair renderer of Xu et al. 2011 on the GPU (wgpu): the CPU renderer's frame
//! (crate `cuticle-render`, its reference, in f64) run in f32, image for image.
//!
//! # The frame, stage by stage as `render.json` times it
//! 1. tables: the parameter-independent tables (𝒞_k/ℋ_k, half-circle integrals, spread
//!    normalisation, the circular-Gaussian width table) uploaded once by [`GpuRenderer::new`];
//!    the lobe table and back-scattering tables uploaded when a hair parameter rebuilds them
//!    ([`tables`]);
//! 2. drawing: strands rasterised into the supersampled visibility buffer and the visible
//!    points listed, on the GPU ([`draw`], frame/draw.rs's rules); the background (the
//!    environment through each pixel) on the CPU meanwhile;
//! 3. shadows: deep opacity maps of every lit light, filtered to its bandwidth, and T̃ at every
//!    visible point, on the GPU ([`shadows`]), into the buffer shading reads;
//! 4. shading: one compute invocation per visible point ([`shading`]: single scattering, dual
//!    scattering; WGSL files named after the CPU files they port), the lights in as many
//!    dispatches as keep an invocation within llvmpipe's loop budget (one for the usual
//!    scenes; [`shading::LOOP_BUDGET`]);
//! 5. resolve: subsamples averaged into pixels on the GPU ([`resolve`]).
//!
//! [`bench`] times it on the paper's workload (`cuticle bench render --device gpu`), with GPU
//! timestamps where the adapter has them; [`strands`] holds the per-strand records.
//!
//! Only what an edit changes is redone: a hair-parameter or paint edit re-runs shading and
//! resolve ([`GpuRenderer::shade`], [`GpuRenderer::update_strands`]); a camera move
//! redraws and rebuilds the shadows, keeping the uploaded tables and strand records
//! ([`GpuRenderer::redraw`]), then re-shades; an environment rotation turns the fitted lights
//! with the map (no fit) and rebuilds the shadows and background only
//! ([`GpuRenderer::relight`]). [`GpuFrame::passes`] counts what ran.
//!
//! # Use (the CLI, the window)
//! ```no_run
//! use cuticle_gpu::{GpuDevice, GpuRenderer, Preference, StrandParams};
//! # fn scene() -> cuticle_render::Scene { unimplemented!() }
//! let device = GpuDevice::new(Preference::Any)?; // or GpuDevice::from_wgpu(...) with eframe's
//! let cpu = cuticle_render::Renderer::new(); // its tables, built once
//! let gpu = GpuRenderer::new(&device, &cpu);
//! let mut scene = scene();
//! let mut frame = gpu.prepare(&scene)?; // drawing + shadows: after a camera/light change
//! let image = gpu.shade(&mut frame, &scene); // shading + resolve: after a hair edit
//! scene.spec.hair.beta_r_deg = 4.0;
//! let edited = gpu.shade(&mut frame, &scene); // re-shades, does not redraw
//! // Painting: strand 12's absorption, without re-uploading the groom (the window should set
//! // the groom's appearance too, so that the CPU renderer agrees).
//! gpu.update_strands(&mut frame, 12, &[StrandParams::new([2.0, 3.0, 5.0])])?;
//! let painted = gpu.shade(&mut frame, &scene); // keeps painted strands while the scene's
//!                                              // absorption (hair.mu_a, default_mu_a) stays
//! let ids = gpu.visibility(&frame); // strand id per subsample, for picking strands to paint
//!                                   // (read back from the GPU's visibility buffer)
//! scene.camera.eye[0] += 1.0;
//! gpu.redraw(&mut frame, &scene)?; // a camera move: drawing and shadows again (the groom
//!                                  // re-sent, no table or strand record)
//! let moved = gpu.shade(&mut frame, &scene);
//! // An environment rotation: turn scene.lights' directions and the map (Scene::from_parts
//! // with env.with_rotation), then
//! gpu.relight(&mut frame, &scene)?; // shadows and background again, no drawing, no fit
//! let turned = gpu.shade(&mut frame, &scene);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//! Every call blocks until the GPU is done; a window calls them from its render worker.
//!
//! # Choosing a device
//! [`choice::Choice`] is `--device auto|gpu|cpu`: `auto` takes a hardware GPU where one
//! exists, else the CPU renderer; `gpu` takes any adapter, a software one (lavapipe) included,
//! and fails with one line when there is none; `cpu` never opens a device.

pub mod bench;
mod buffers;
pub mod choice;
pub mod device;
pub mod draw;
pub mod frame;
pub mod groom;
pub mod renderer;
pub mod resolve;
pub mod shading;
pub mod shadows;
pub mod strands;
pub mod tables;

pub use choice::{Backend, Choice};
pub use device::{AdapterSummary, DeviceError, GpuDevice, Preference};
pub use frame::{GpuFrame, GpuSeconds, Passes, Visibility};
pub use renderer::{GpuError, GpuRenderer};
pub use strands::{StrandError, StrandParams};
