"""Chapaev for Python: the match server's exact shot simulation.

Every value has the wire protocol's JSON shape (docs/protocol.md): plain
dicts, lists, ints and floats. The TypedDicts below name those shapes; they
exist for type checkers only (import them under `typing.TYPE_CHECKING`).
"""

import array
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, TypedDict, Union, final

__version__: str
PROTOCOL_VERSION: int
PLAY_MANY_STRIDE: int
"""Floats per shot in the answer of `Simulator.play_many` (56)."""

Vec2 = List[float]
"""`[x, y]` in metres, or `[vx, vy]` in m/s (a tuple is accepted as input)."""

SideName = Literal["white", "black"]
ErrorCode = str
"""A wire error code: `bad-message`, `bad-board`, `bad-config`, `not-finite`,
`zero-speed`, `too-fast`, `not-your-piece`, `piece-off-board`, `internal`."""

class Piece(TypedDict):
    """A piece on the board: `id` 0-7 White's (files a-h), 8-15 Black's."""

    id: int
    pos: Vec2

class NoiseConfig(TypedDict):
    """Gaussian execution noise: standard deviations of the angle (rad) and the speed (fraction)."""

    angle_sigma: float
    speed_sigma: float

class Variants(TypedDict, total=False):
    two_row_advance: bool
    pie_rule: bool
    quick_match: bool
    noise: Optional[NoiseConfig]

class Config(TypedDict, total=False):
    """A game configuration (`view.config` of a match); missing fields take the defaults."""

    square: float
    piece_radius: float
    piece_mass: float
    mu: float
    g: float
    restitution: float
    max_speed: float
    max_events_per_shot: int
    variants: Variants

class NoiseDraw(TypedDict):
    """One draw of execution noise: two standard normal numbers."""

    angle: float
    speed: float

class _SimulateRequestRequired(TypedDict):
    board: List[Piece]
    piece: int
    velocity: Vec2

class SimulateRequest(_SimulateRequestRequired, total=False):
    """One shot to simulate (the default casual config when `config` is left out)."""

    config: Config
    noise: Optional[NoiseDraw]
    film: bool

class RoundResult(TypedDict, total=False):
    result: Literal["won", "draw"]
    side: SideName

class Verdict(TypedDict, total=False):
    """`{"verdict": "shoot-again"}`, `{"verdict": "pass-turn"}` or
    `{"verdict": "round-over", "result": "won", "side": "white"}` (or `"result": "draw"`)."""

    verdict: Literal["shoot-again", "pass-turn", "round-over"]
    result: Literal["won", "draw"]
    side: SideName

class Film(TypedDict):
    """Every piece's motion during a shot: the engine's snapshot at t = 0 and
    the changes at each event (see docs/protocol.md, `shot-played`)."""

    start: Dict[str, Any]
    diffs: List[Dict[str, Any]]
    end: float

EndReason = Literal["rest", "free", "until", "max-collisions", "max-events"]

class _SimulationRequired(TypedDict):
    played: Vec2
    knocked_off: List[int]
    board: List[Piece]
    verdict: Verdict
    duration: float
    end_reason: EndReason

class Simulation(_SimulationRequired, total=False):
    """What one simulated shot did; `film` only when asked for."""

    film: Film

class ScenePiece(TypedDict):
    id: int
    pos: Vec2
    vel: Vec2

class Scene(TypedDict):
    t: float
    pieces: List[ScenePiece]

class SimulateError(ValueError):
    """A request was refused (or malformed: code `bad-message`)."""

    code: ErrorCode
    message: str

def simulate(request: SimulateRequest) -> Simulation:
    """Validates and simulates one shot, exactly as the server would."""

class Verification(TypedDict):
    """What `verify` checked of a finished match."""

    scheme: str
    commitment: str
    shots: int
    draws: List[NoiseDraw]

def verify(record: Union[str, Dict[str, Any]]) -> Verification:
    """Checks a finished match's record (JSON text or parsed): the revealed
    secret opens the commitment, every shot's `played` velocity is its
    `aimed` one under the secret's draw, and the match replays to every
    outcome. Raises `SimulateError` with `code` `commitment-mismatch`,
    `noise-mismatch`, `replay-diverged`, `secret-not-revealed`,
    `uncommitted`, `bad-record` or `unsupported-physics`."""

@final
class Simulator:
    """One position, checked and converted once, to score many shots on."""

    def __new__(cls, config: Optional[Config], board: List[Piece]) -> "Simulator": ...
    def play(
        self,
        piece: int,
        velocity: Union[Vec2, Tuple[float, float]],
        noise: Optional[NoiseDraw] = None,
    ) -> Simulation:
        """The shot as `simulate` plays it (no film), with the aimed velocity and an optional draw."""
    def play_many(self, shots: Union[Sequence[float], "array.array[float]"]) -> List[float]:
        """Many shots in one call, the very bits of `play` on each.

        `shots` holds 5 numbers per shot: `piece, vx, vy, noise_angle,
        noise_speed` (`nan, nan` for no noise draw; the draw is applied only
        when the configuration has a noise model). The answer holds
        `PLAY_MANY_STRIDE` (56) floats per shot (shot `k` at `56 * k`):

        - 0: status: 0.0 played, else the refusal `play` would raise:
          1 bad-message (the piece is not an integer id 0 to 15),
          2 not-finite, 3 zero-speed, 4 too-fast, 5 piece-off-board,
          6 internal, 7 other;
        - 1: verdict: 0 shoot-again, 1 pass-turn, 2 round over (White won),
          3 round over (Black won), 4 round over (draw);
        - 2, 3: the velocity played (after noise);
        - 4: duration, s after the flick;
        - 5: end reason: 0 rest, 1 free, 2 until, 3 max-collisions,
          4 max-events;
        - 6, 7: how many White, Black pieces were knocked off;
        - 8 to 23: the ids knocked off, in the order they fell, then nan;
        - 24 to 55: `x, y` of piece id `i` at rest at `24 + 2 * i`, nan
          when that piece is not on the board.

        A refused shot raises nothing: it has its status and nan elsewhere.
        Raises `SimulateError` (`bad-message`) only when the length is not a
        multiple of 5.
        """
    @property
    def config(self) -> Config: ...
    @property
    def board(self) -> List[Piece]: ...

def validate_shot(
    config: Optional[Config],
    board: List[Piece],
    side: SideName,
    piece: int,
    velocity: Union[Vec2, Tuple[float, float]],
) -> Optional[Tuple[ErrorCode, str]]:
    """None if `side` may flick `piece` at `velocity`, else `(code, message)`."""

def legal_pieces(board: List[Piece], side: SideName) -> List[int]:
    """The ids of `side`'s pieces on `board`, in id order."""

def default_config() -> Config:
    """The default (casual) configuration: no noise, no pie rule."""

def standard_config() -> Config:
    """The standard configuration: execution noise and the pie rule."""

def config_for(rules: Literal["casual", "standard"]) -> Config:
    """The configuration of the named rules."""

def scene_at(film: Film, t: float) -> Scene:
    """The pieces on the board at time `t` of a shot (clamped to `[0, film["end"]]`)."""

@final
class NoiseRng:
    """A bot's own noise draws: exactly `NoiseDraw::sample` on `SplitMix64::new(seed)`."""

    def __new__(cls, seed: int) -> "NoiseRng": ...
    def sample(self) -> NoiseDraw: ...
    def next_u64(self) -> int: ...
    def next_f64(self) -> float: ...

def apply_noise(
    config: Optional[Config],
    velocity: Union[Vec2, Tuple[float, float]],
    draw: NoiseDraw,
) -> Vec2:
    """The velocity played when `velocity` is aimed with `draw` (as aimed without a noise model)."""

def random_requests(seed: int, n: int) -> List[SimulateRequest]:
    """`n` random requests from one generator seeded with `seed` (for tests and benchmarks)."""
