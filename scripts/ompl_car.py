"""OMPL (pip `ompl` 2.0.1) on the parking problem of benches/car_parking_ompl.scen.

The peer of issue 23: a Reeds-Shepp car (ReedsSheppStateSpace, turning
radius 4.5) planned with OMPL's RRTConnect or RRT* (stopping at the first
exact solution), as a Python user of OMPL writes it.

Validity is exact and sound for motions: a state is valid when the car's
body (a convex polygon) is inside the bounds and separated (separating-axis
test) from every obstacle grown by CLEARANCE / 2; OMPL's discrete motion
validator checks states at most STEP apart in arc length, and STEP is chosen
so that no point of the body moves more than CLEARANCE / 2 between a checked
state and any state in between (a body point at distance r from the rear
axle moves at most s * (1 + r / radius) along s of path). So every motion
OMPL accepts is collision-free in the world as written, at the price of
keeping CLEARANCE / 2 from the obstacles.

Usage: python scripts/ompl_car.py PLANNER SEED [TIME_LIMIT]
Prints one line: planner seed solved time length states checks
       python scripts/ompl_car.py --world
Prints the problem as JSON (tests/steer_ompl.rs compares it with the
scenario's).
"""

import json
import math
import sys
import time

from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou

# The parking problem (benches/car_parking_ompl.scen).
BOUNDS = (0.0, 0.0, 30.0, 12.0)
OBSTACLES = [
    (0.0, 0.0, 30.0, 1.0),  # kerb
    (5.0, 1.2, 10.0, 3.0),  # rear_car
    (18.0, 1.2, 23.0, 3.0),  # front_car
]
BODY = [(-1.0, -0.9), (3.5, -0.9), (3.5, 0.9), (-1.0, 0.9)]
RADIUS = 4.5
START = (2.0, 7.0, 0.0)
GOAL = (11.5, 2.2, 0.0)

CLEARANCE = 0.02
REACH = max(math.hypot(x, y) for x, y in BODY)
STEP = CLEARANCE / (1.0 + REACH / RADIUS)

HALF = CLEARANCE / 2.0
GROWN = [(x0 - HALF, y0 - HALF, x1 + HALF, y1 + HALF) for x0, y0, x1, y1 in OBSTACLES]
INNER = (BOUNDS[0] + HALF, BOUNDS[1] + HALF, BOUNDS[2] - HALF, BOUNDS[3] - HALF)


def corners(x, y, t):
    c, s = math.cos(t), math.sin(t)
    return [(x + c * bx - s * by, y + s * bx + c * by) for bx, by in BODY]


def separated(pts, rect, axes):
    """Whether an axis of the body or of the rectangle separates them."""
    x0, y0, x1, y1 = rect
    xs = [p[0] for p in pts]
    ys = [p[1] for p in pts]
    if max(xs) <= x0 or min(xs) >= x1 or max(ys) <= y0 or min(ys) >= y1:
        return True
    rc = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    for ax, ay in axes:
        pa = [ax * px + ay * py for px, py in pts]
        pr = [ax * px + ay * py for px, py in rc]
        if max(pa) <= min(pr) or max(pr) <= min(pa):
            return True
    return False


CHECKS = 0


def valid(state):
    global CHECKS
    CHECKS += 1
    x, y, t = state.getX(), state.getY(), state.getYaw()
    pts = corners(x, y, t)
    for px, py in pts:
        if px < INNER[0] or px > INNER[2] or py < INNER[1] or py > INNER[3]:
            return False
    c, s = math.cos(t), math.sin(t)
    axes = [(c, s), (-s, c)]
    return all(separated(pts, r, axes) for r in GROWN)


def main():
    if sys.argv[1] == "--world":
        print(json.dumps({
            "bounds": BOUNDS, "obstacles": OBSTACLES, "body": BODY,
            "radius": RADIUS, "start": START, "goal": GOAL,
        }))
        return
    planner_name = sys.argv[1]
    seed = int(sys.argv[2])
    limit = float(sys.argv[3]) if len(sys.argv) > 3 else 60.0
    ou.setLogLevel(ou.LOG_ERROR)
    ou.RNG.setSeed(seed)
    space = ob.ReedsSheppStateSpace(RADIUS)
    bounds = ob.RealVectorBounds(2)
    bounds.setLow(0, BOUNDS[0])
    bounds.setLow(1, BOUNDS[1])
    bounds.setHigh(0, BOUNDS[2])
    bounds.setHigh(1, BOUNDS[3])
    space.setBounds(bounds)
    # OMPL's distance is the path length (radius times the unit length).
    space.setLongestValidSegmentFraction(STEP / space.getMaximumExtent())
    setup = og.SimpleSetup(space)
    setup.setStateValidityChecker(valid)
    start, goal = space.allocState(), space.allocState()
    for st, (x, y, t) in ((start, START), (goal, GOAL)):
        st.setX(x)
        st.setY(y)
        st.setYaw(t)
    setup.setStartAndGoalStates(start, goal)
    si = setup.getSpaceInformation()
    planner = {"rrt_connect": og.RRTConnect, "rrt_star": og.RRTstar}[planner_name](si)
    setup.setPlanner(planner)
    # RRT* stops at its first solution (scen's `stop first`): every cost
    # satisfies an objective whose threshold is infinite.
    objective = ob.PathLengthOptimizationObjective(si)
    objective.setCostThreshold(ob.Cost(math.inf))
    setup.setOptimizationObjective(objective)
    setup.setup()
    pdef = setup.getProblemDefinition()
    stop = ob.plannerOrTerminationCondition(
        ob.timedPlannerTerminationCondition(limit),
        ob.exactSolnPlannerTerminationCondition(pdef),
    )
    t0 = time.perf_counter()
    planner.solve(stop)
    elapsed = time.perf_counter() - t0
    solved = pdef.hasExactSolution()
    length = float("nan")
    if solved:
        length = pdef.getSolutionPath().length()
    data = ob.PlannerData(si)
    planner.getPlannerData(data)
    print(
        f"{planner_name} {seed} {int(solved)} {elapsed:.4f} {length:.4f} {data.numVertices()} {CHECKS}"
    )


if __name__ == "__main__":
    main()
