//! Chapaev online in the browser (skeleton; the screens are being written).
mod platform;

use macroquad::prelude::*;

fn conf() -> Conf {
    Conf {
        window_title: "Chapaev online".to_owned(),
        window_width: 1024,
        window_height: 720,
        high_dpi: false,
        ..Default::default()
    }
}

#[macroquad::main(conf)]
async fn main() {
    let mut ready = false;
    loop {
        clear_background(Color::from_rgba(40, 30, 24, 255));
        draw_text("Chapaev online", 20.0, 40.0, 32.0, WHITE);
        let w = screen_width();
        platform::report(&format!(
            r#"{{"screen":"lobby","buttons":{{"vs-computer-easy":[{},{},200,40]}}}}"#,
            w / 2.0 - 100.0,
            200
        ));
        if !ready {
            platform::set_ready();
            ready = true;
        }
        next_frame().await
    }
}
