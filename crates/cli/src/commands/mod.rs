pub mod furnace;
pub mod lobes;
pub mod groom;
