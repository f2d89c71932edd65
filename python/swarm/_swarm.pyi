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
