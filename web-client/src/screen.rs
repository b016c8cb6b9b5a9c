//! What every screen of the app is: something drawn and updated once a
//! frame that may ask to go somewhere else.

use crate::route::Route;
use crate::ui::Ui;

/// One screen (lobby, match, replay, sandbox).
pub trait Screen {
    /// Runs one frame: reads `ui.input`, updates, draws. `dt` is the wall
    /// time since the last frame in seconds. Returns a route to leave for.
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route>;

    /// The screen's name in the state report (`lobby`, `play`, ...).
    fn name(&self) -> &'static str;

    /// Extra facts for the state report the browser test reads (fields
    /// merged into `window.chapaev_state`). The default reports nothing.
    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        serde_json::Map::new()
    }

    /// Whether something moves on screen, so the app must keep drawing at
    /// full rate. The default is `false`.
    fn animating(&self) -> bool {
        false
    }
}
