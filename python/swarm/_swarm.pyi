# Type stubs of the native module (python/src/lib.rs).
from typing import Any, Dict, List, Optional, Sequence, Tuple

class SwarmError(Exception):
    """An error of the simulator; its message is the `swarm` command's."""

def builtin_names() -> List[str]: ...
def models() -> List[Tuple[str, int, str]]: ...
def load(name_or_path: str) -> Tuple[str, Optional[str]]: ...
def check(scenario: str, source: Optional[str] = None) -> str: ...
def run(
    scenario: str,
    source: Optional[str] = None,
    *,
    backend: Optional[str] = None,
    seed: Optional[int] = None,
    steps: Optional[int] = None,
    threads: Optional[int] = None,
    progress: bool = False,
) -> Dict[str, Any]: ...
def evaluate_tracks(
    reference: Any,
    candidates: Sequence[Any],
    *,
    dt: Optional[float] = None,
    scaling: str = "separate",
) -> str: ...
def run_to(
    scenario: str,
    source: Optional[str],
    out: str,
    *,
    backend: Optional[str] = None,
    seed: Optional[int] = None,
    steps: Optional[int] = None,
    threads: Optional[int] = None,
) -> str: ...
def read_tracks(path: str, dt: Optional[float] = None) -> Tuple[Any, float]: ...
def score(reference: Any, candidate: Any, *, dt: Optional[float] = None,
          scaling: str = "reference") -> float: ...
def simulate(
    scenario: str,
    source: Optional[str] = None,
    *,
    seeds: Sequence[int],
    burn_in: int,
    frames: int,
    every: int = 1,
    backend: Optional[str] = None,
    threads: Optional[int] = None,
) -> Any: ...
def parameters(model: str) -> List[Tuple[str, str, float, float, bool, str]]: ...
def whole_range(model: str, name: str) -> Tuple[float, float]: ...

class GeneticAlgorithm:
    """The genetic algorithm of `swarm fit`, asked and told one generation at a time."""

    def __init__(
        self,
        ranges: Sequence[Tuple[float, float]],
        *,
        population: Optional[int] = None,
        generations: Optional[int] = None,
        crossover: Optional[float] = None,
        mutation: Optional[float] = None,
        seed: int = 1,
    ) -> None: ...
    def ask(self) -> List[List[float]]: ...
    def tell(self, scores: Sequence[float]) -> None: ...
    @property
    def done(self) -> bool: ...
    @property
    def history(self) -> List[float]: ...
    def best(self) -> Tuple[List[float], float, int]: ...
