use game::noise::SplitMix64;
use game::*;
use glam::DVec2;

fn main() {
    for seed in 0..5u64 {
        let mut c = Config::default();
        c.variants.noise = Some(NoiseConfig { angle_sigma: 0.01, speed_sigma: 0.03 });
        c.variants.pie_rule = true;
        c.variants.two_row_advance = true;
        let mut game = Game::new(c, seed).unwrap();
        let mut rng = SplitMix64::new(seed ^ 0xC4A9_AE5E);
        while !game.is_over() {
            match game.phase() {
                Phase::Over { .. } => {}
                Phase::PieDecision => {
                    let swap = rng.next_u64() & 1 == 0;
                    game.decide_pie(Side::Black, swap).unwrap();
                }
                Phase::Shooting => {
                    let side = game.to_shoot().unwrap();
                    if rng.next_f64() < 1.0 / 2000.0 {
                        game.resign(side).unwrap();
                        continue;
                    }
                    let config = game.config().clone();
                    let own: Vec<_> = game.board().of(side).copied().collect();
                    let enemy: Vec<_> = game.board().of(side.opponent()).copied().collect();
                    let me = own[(rng.next_u64() % own.len() as u64) as usize];
                    let dir = if rng.next_f64() < 0.75 {
                        let target = enemy[(rng.next_u64() % enemy.len() as u64) as usize];
                        let d = target.pos - me.pos;
                        d + DVec2::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5) * config.square
                    } else {
                        let (s, c) = game::noise::sin_cos(rng.next_f64() * std::f64::consts::TAU);
                        DVec2::new(c, s)
                    };
                    let speed = config.max_speed * (0.05 + 0.95 * rng.next_f64());
                    let shot = Shot::aimed(me.id, dir, speed, &config).unwrap();
                    game.play(side, shot).unwrap();
                }
            }
        }
        let json = game.record().to_json();
        let mut h: u64 = 0xcbf29ce484222325;
        for b in json.bytes() {
            h = (h ^ b as u64).wrapping_mul(0x100000001b3);
        }
        let replay = Replay::from_json(&json).unwrap();
        println!("HASH seed {seed} shots {} hash {h:016x} replay-ok {}", game.shots(), replay.shot_count());
    }
    let n = NoiseConfig { angle_sigma: 0.05, speed_sigma: 0.1 };
    let v = game::noise::perturb(&n, 77, 12, DVec2::new(0.3, -1.1), 2.0);
    println!("HASH noise {:016x} {:016x}", v.x.to_bits(), v.y.to_bits());
}
