//! Prints the versions this build of the rules plays under, as one JSON
//! line: `{"physics_version":N,"protocol_version":M}`. `scripts/build-sdk`
//! writes them into the SDK's manifest, which the server checks against
//! its own before it hands the packages out.
fn main() {
    println!(
        "{}",
        serde_json::json!({
            "physics_version": game::PHYSICS_VERSION,
            "protocol_version": game::protocol::PROTOCOL_VERSION,
        })
    );
}
