//! When the app draws a frame. In the browser it draws only while something
//! changes: while a screen animates, while the player's pointer, fingers or
//! keys are busy, and for a moment after each of those (a click's screen
//! change, a request it started), then it waits. An event from the browser
//! (input, a WebSocket message, an HTTP reply, pasted text, an edited
//! address) wakes a frame at once, and a heartbeat in `js/chapaev.js`
//! wakes one twice a second, so clocks, polls and the state report go on
//! while nothing happens. An idle page then costs a phone two frames a
//! second instead of sixty (a full redraw each, at three device pixels to
//! the CSS pixel).
//!
//! This is miniquad's blocking event loop: a frame runs when an event or
//! [`Pace::end_frame`] schedules one. On the desktop the loop is not
//! blocking and every frame is drawn.

use macroquad::miniquad::window::{blocking_event_loop, schedule_update};
use macroquad::prelude::*;

/// How long the app keeps drawing every frame after the last sign of
/// activity, in seconds.
const LINGER: f64 = 0.75;

/// Whether the event loop blocks between frames: in the browser only, where
/// `js/chapaev.js` wakes it (on the desktop nothing would).
pub const BLOCKING: bool = cfg!(target_arch = "wasm32");

/// The inputs that wake the waiting loop: all of them. A key's release and
/// a typed character need no trigger of their own, as their key went down
/// first and the frames after it linger.
pub fn wake_on_input() -> macroquad::conf::UpdateTrigger {
    macroquad::conf::UpdateTrigger {
        key_down: true,
        mouse_down: true,
        mouse_up: true,
        mouse_motion: true,
        mouse_wheel: true,
        specific_key: None,
        touch: true,
    }
}

/// What the player is doing with the input devices, to tell a frame with
/// input from one without.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Hands {
    pointer: (f32, f32),
    buttons: [bool; 3],
    touches: usize,
    keys: usize,
}

impl Hands {
    fn now() -> Hands {
        Hands {
            pointer: mouse_position(),
            buttons: [MouseButton::Left, MouseButton::Right, MouseButton::Middle]
                .map(is_mouse_button_down),
            touches: touches().len(),
            keys: get_keys_down().len(),
        }
    }

    fn busy(&self) -> bool {
        self.buttons.iter().any(|&b| b) || self.touches > 0 || self.keys > 0
    }
}

/// The longest time step a frame hands the screens while something moves:
/// a hidden tab gets no frames, and an animation must not jump when it
/// comes back.
const MAX_STEP: f64 = 0.1;

/// The frame pacer: one per app, asked at the start and end of every frame.
#[derive(Debug, Default)]
pub struct Pace {
    /// Draw every frame until this time (`get_time`).
    until: f64,
    last: Hands,
    /// The last frame left the loop waiting for an event.
    waited: bool,
}

impl Pace {
    /// The time step for a frame that comes `gap` seconds after the last:
    /// at most [`MAX_STEP`] after a frame that kept the loop running
    /// (something moved), the whole gap after a wait (nothing moved, and
    /// clocks and timers must keep the real time).
    pub fn step(&self, gap: f64) -> f64 {
        if self.waited {
            gap
        } else {
            gap.min(MAX_STEP)
        }
    }

    /// Ends a frame at `now`: `active` when the screen animates or changed.
    /// Schedules the next frame at once while anything is going on (or
    /// went on less than [`LINGER`] ago); otherwise the next frame waits for
    /// an event or the heartbeat.
    pub fn end_frame(&mut self, now: f64, active: bool) {
        let hands = Hands::now();
        if active || hands.busy() || hands != self.last {
            self.until = now + LINGER;
        }
        self.last = hands;
        self.waited = blocking_event_loop() && now >= self.until;
        if blocking_event_loop() && !self.waited {
            schedule_update();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_after_a_wait_gets_the_whole_gap_and_one_while_moving_is_capped() {
        let moving = Pace::default();
        assert_eq!(moving.step(0.016), 0.016);
        assert_eq!(moving.step(3.0), MAX_STEP);
        let waited = Pace {
            waited: true,
            ..Pace::default()
        };
        assert_eq!(waited.step(0.5), 0.5);
        assert_eq!(waited.step(42.0), 42.0);
    }
}
