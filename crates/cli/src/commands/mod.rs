pub mod env;
pub mod fiber_args;
pub mod furnace;
pub mod groom;
pub mod lobes;
pub mod render;
pub mod sim;
pub mod sweep;
