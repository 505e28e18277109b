//! The wgpu device the back end runs on: any adapter (discrete, integrated or software), chosen
//! once at start, or one a caller already has (the window's, through [`GpuDevice::from_wgpu`]).

use std::fmt;

/// Which adapters [`GpuDevice::new`] may take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preference {
    /// Hardware only (discrete, integrated or virtual GPU): what `--device auto` asks before
    /// it falls back to the CPU renderer.
    Hardware,
    /// Hardware first, else a software adapter such as lavapipe: what `--device gpu` asks.
    Any,
}

/// What the adapter is, as `render.json` records it.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct AdapterSummary {
    pub name: String,
    /// `discrete`, `integrated`, `virtual`, `software` or `other`.
    pub kind: &'static str,
    pub backend: String,
    pub driver: String,
    /// Whether GPU timestamp queries time each stage.
    pub timestamps: bool,
}

/// Why no device could be had.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DeviceError {
    #[error(
        "no GPU adapter found{found} (for a software one: apt-get install -y mesa-vulkan-drivers libvulkan1)"
    )]
    NoAdapter { found: String },
    #[error("the GPU adapter {adapter} refused a device: {reason}")]
    Refused { adapter: String, reason: String },
}

/// A device, its queue and what the adapter is.
#[derive(Clone)]
pub struct GpuDevice {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub summary: AdapterSummary,
}

impl fmt::Debug for GpuDevice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GpuDevice")
            .field("summary", &self.summary)
            .finish()
    }
}

/// The rank of an adapter kind: lower is preferred; software last.
fn rank(kind: wgpu::DeviceType) -> u8 {
    match kind {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    }
}

fn kind_name(kind: wgpu::DeviceType) -> &'static str {
    match kind {
        wgpu::DeviceType::DiscreteGpu => "discrete",
        wgpu::DeviceType::IntegratedGpu => "integrated",
        wgpu::DeviceType::VirtualGpu => "virtual",
        wgpu::DeviceType::Other => "other",
        wgpu::DeviceType::Cpu => "software",
    }
}

impl GpuDevice {
    /// The best adapter `preference` allows, with a device of its limits and, where it has
    /// them, timestamp queries.
    pub fn new(preference: Preference) -> Result<Self, DeviceError> {
        // Vulkan, Metal and DX12 only: probing GL through EGL connects to a display server and
        // prints the driver's complaints (e.g. about XDG_RUNTIME_DIR) on a headless machine.
        let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle();
        descriptor.backends = wgpu::Backends::PRIMARY;
        let instance = wgpu::Instance::new(descriptor);
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::PRIMARY));
        let usable = |a: &wgpu::Adapter| {
            let info = a.get_info();
            let hardware = info.device_type != wgpu::DeviceType::Cpu;
            (preference == Preference::Any || hardware)
                && a.get_downlevel_capabilities().is_webgpu_compliant()
        };
        let found = adapters
            .iter()
            .map(|a| {
                format!(
                    "{} ({})",
                    a.get_info().name,
                    kind_name(a.get_info().device_type)
                )
            })
            .collect::<Vec<_>>();
        let adapter = adapters
            .into_iter()
            .filter(usable)
            .min_by_key(|a| rank(a.get_info().device_type))
            .ok_or_else(|| DeviceError::NoAdapter {
                found: match (found.is_empty(), preference) {
                    (true, _) => String::new(),
                    (false, Preference::Hardware) => {
                        format!(" but software ones ({})", found.join(", "))
                    }
                    (false, Preference::Any) => format!(" usable among {}", found.join(", ")),
                },
            })?;
        Self::open(&adapter)
    }

    fn open(adapter: &wgpu::Adapter) -> Result<Self, DeviceError> {
        let info = adapter.get_info();
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let required_features = if timestamps {
            wgpu::Features::TIMESTAMP_QUERY
        } else {
            wgpu::Features::empty()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("cuticle-gpu"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| DeviceError::Refused {
            adapter: info.name.clone(),
            reason: e.to_string(),
        })?;
        Ok(Self {
            device,
            queue,
            summary: AdapterSummary {
                name: info.name.clone(),
                kind: kind_name(info.device_type),
                backend: format!("{:?}", info.backend).to_lowercase(),
                driver: format!("{} {}", info.driver, info.driver_info)
                    .trim()
                    .to_string(),
                timestamps,
            },
        })
    }

    /// A device someone else opened (the window's, so that its frames and ours share one
    /// device). It must have wgpu's default limits at least; timestamps are used if it was
    /// opened with [`wgpu::Features::TIMESTAMP_QUERY`].
    pub fn from_wgpu(device: wgpu::Device, queue: wgpu::Queue, info: &wgpu::AdapterInfo) -> Self {
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        Self {
            device,
            queue,
            summary: AdapterSummary {
                name: info.name.clone(),
                kind: kind_name(info.device_type),
                backend: format!("{:?}", info.backend).to_lowercase(),
                driver: info.driver.clone(),
                timestamps,
            },
        }
    }

    /// Whether the adapter is a software one (lavapipe).
    pub fn is_software(&self) -> bool {
        self.summary.kind == "software"
    }
}
