//! The lobby (being written).

use crate::route::Route;
use crate::screen::Screen;
use crate::ui::Ui;
use macroquad::prelude::Rect;

pub struct Lobby;

impl Lobby {
    pub fn new() -> Lobby {
        Lobby
    }
}

impl Screen for Lobby {
    fn frame(&mut self, ui: &mut Ui, _dt: f64) -> Option<Route> {
        ui.button("sandbox", "Sandbox", Rect::new(10.0, 10.0, 100.0, 32.0))
            .then_some(Route::Sandbox)
    }
    fn name(&self) -> &'static str {
        "lobby"
    }
}
