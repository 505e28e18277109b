pub mod furnace;
pub mod lobes;
