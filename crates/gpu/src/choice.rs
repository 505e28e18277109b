//! `--device auto|gpu|cpu`: which renderer a command runs.

use crate::device::{DeviceError, GpuDevice, Preference};

/// The `--device` flag.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Choice {
    /// A hardware GPU where one exists, else the CPU renderer.
    Auto,
    /// Any GPU adapter, a software one included; an error when there is none.
    Gpu,
    /// The CPU renderer.
    Cpu,
}

impl std::str::FromStr for Choice {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(Self::Auto),
            "gpu" => Ok(Self::Gpu),
            "cpu" => Ok(Self::Cpu),
            _ => Err(format!("--device takes auto, gpu or cpu, got {s}")),
        }
    }
}

/// What a [`Choice`] resolved to.
#[derive(Debug)]
pub enum Backend {
    Cpu,
    Gpu(GpuDevice),
}

impl Backend {
    /// Resolves `choice`: only `gpu` can fail (no adapter at all).
    pub fn choose(choice: Choice) -> Result<Self, DeviceError> {
        match choice {
            Choice::Cpu => Ok(Self::Cpu),
            Choice::Gpu => GpuDevice::new(Preference::Any).map(Self::Gpu),
            Choice::Auto => Ok(GpuDevice::new(Preference::Hardware).map_or(Self::Cpu, Self::Gpu)),
        }
    }
}
