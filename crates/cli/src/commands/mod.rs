pub mod furnace;
pub mod lobes;
pub mod groom;
pub mod sim;
pub mod sweep;
pub mod env;
