# Type stubs of the extension module scen._scen (crates/python/src/lib.rs).
from os import PathLike
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class ScenError(Exception):
    """Bad input. `diagnostics`: one dict per problem, with `severity`,
    `code`, `message`, `label`, `help`, and `file`, `line`, `column`,
    `end_line`, `end_column` when located."""

    diagnostics: List[Dict[str, Any]]

def load(
    path: Union[str, PathLike[str]],
    *,
    root: Optional[Union[str, PathLike[str]]] = None,
    sample: int = 0,
    family_seed: int = 0,
) -> Scenario:
    """Reads a scenario file (its includes and maps inside its folder, or `root`);
    for a family, sample `sample` drawn from `family_seed`."""

def loads(
    text: str,
    *,
    name: str = "<string>.scen",
    root: Optional[Union[str, PathLike[str]]] = None,
    sample: int = 0,
    family_seed: int = 0,
) -> Scenario:
    """Reads a scenario from its text, reported as the file `name`."""

def plan(
    grid: npt.ArrayLike,
    start: Sequence[float],
    goal: Optional[Sequence[float]] = None,
    *,
    planner: str = "astar",
    robot: str = "point",
    cell: float = 1.0,
    origin: Tuple[float, float] = (0.0, 0.0),
    **params: Any,
) -> PlanResult:
    """Plans on a 2-D numpy grid (True or non-zero: blocked; row 0 the top row)
    from `start` to `goal` (x, y[, theta]); `params` are the planner's."""

def bench_merge(paths: Sequence[Union[str, PathLike[str]]], *, root: Optional[Union[str, PathLike[str]]] = None) -> Report:
    """`scen bench merge`: the whole bench from its shards' part files."""

class Scenario:
    @property
    def title(self) -> Optional[str]: ...
    @property
    def file(self) -> str: ...
    @property
    def family(self) -> Optional[Dict[str, Any]]:
        """A family's sample: sample, family_seed, params; None otherwise."""
    def sample(self, k: int) -> Scenario:
        """Sample k of the same family (itself when it draws nothing)."""
    @property
    def plans(self) -> List[str]:
        """The plans' names, in order."""
    @property
    def planners(self) -> List[Tuple[str, str]]:
        """(plan, planner) for each plan."""
    def run(self, plans: Optional[Sequence[str]] = None, *, seed: Optional[int] = None, draw: bool = False) -> Report:
        """Runs the plans (all, or those named), validates every path and
        evaluates the checks; the GIL is released meanwhile."""
    def validate(self, plan: str, path: npt.NDArray[np.float64]) -> Report:
        """The validator on an (N, 2), (N, 3) or (N, 4) array (x, y[, theta[, t]])
        as if plan `plan` had returned it."""
    @property
    def benches(self) -> List[str]:
        """The benches' names, in order."""
    def bench(self, benches: Optional[Sequence[str]] = None, *, runs: Optional[int] = None, worlds: Optional[int] = None) -> Report:
        """Runs the benches as `scen bench` does (the GIL released)."""
    def bench_part(
        self, k: int, n: int, *, benches: Optional[Sequence[str]] = None, runs: Optional[int] = None, worlds: Optional[int] = None
    ) -> str:
        """Shard k of n: the text of the part `scen bench --shard K/N --out` writes."""
    def to_svg(self) -> str: ...
    def _repr_svg_(self) -> str: ...

class Report:
    @property
    def plans(self) -> Dict[str, PlanResult]: ...
    @property
    def checks(self) -> List[Dict[str, Any]]:
        """Each evaluated check: line, expr, passed, values."""
    @property
    def passed(self) -> int: ...
    @property
    def failed(self) -> int: ...
    @property
    def bench_runs(self) -> List[Dict[str, Any]]:
        """A bench's runs: bench, plan, config, world, run, seed, metrics."""
    def bench_table(self, metrics: Optional[Sequence[str]] = None) -> str:
        """A bench's tables, as `scen bench` prints them."""
    def to_json(self) -> str:
        """The document `scen run --json` prints (`scen bench --json`'s for a bench)."""
    def to_svg(self) -> str: ...
    def _repr_svg_(self) -> str: ...
    def __getitem__(self, plan: str) -> PlanResult: ...

class PlanResult:
    name: str
    planner: str
    found: bool
    valid: bool
    metrics: Dict[str, Union[int, float, bool, None]]
    path: Optional[npt.NDArray[np.float64]]
    """(N, 2) x, y, or (N, 3) x, y, theta when the robot's heading matters."""
    trajectory: Optional[npt.NDArray[np.float64]]
    """(N, 4) x, y, theta, t for a time-aware plan."""
    segments: Optional[List[Tuple[str, float]]]
    agents: Optional[Dict[str, npt.NDArray[np.float64]]]
    """A team plan's agents: name -> (N, 2) x, y, one row per step; (N, 4) x, y, theta, t for `prioritized`."""
    collision: Optional[Dict[str, Any]]
    """segment, at (x, y, theta), obstacle, reason; None when valid."""
    def to_svg(self) -> str:
        """This plan's run drawn alone (its world, search layers if drawn, path)."""
    def _repr_svg_(self) -> str: ...
