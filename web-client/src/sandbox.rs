//! The offline physics sandbox (being written).

use crate::route::Route;
use crate::screen::Screen;
use crate::ui::Ui;
use macroquad::prelude::Rect;

pub struct Sandbox;

impl Sandbox {
    pub fn new() -> Sandbox {
        Sandbox
    }
}

impl Screen for Sandbox {
    fn frame(&mut self, ui: &mut Ui, _dt: f64) -> Option<Route> {
        ui.button("lobby", "Lobby", Rect::new(10.0, 10.0, 100.0, 32.0))
            .then_some(Route::Lobby)
    }
    fn name(&self) -> &'static str {
        "sandbox"
    }
}
