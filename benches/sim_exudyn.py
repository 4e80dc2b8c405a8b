"""The benchmark mechanisms as Exudyn models (rigid bodies in the plane, revolute joints: an index-3 DAE in absolute
co-ordinates) and the solver that times them: Exudyn's implicit generalized-alpha method, whose step is fixed
(``numberOfSteps``), so its accuracy is set by the step count rather than a tolerance.

Each body's node sits at its centre of mass with the rotation of the mechfem element's frame (u-axis along P->Q), so
the benchmark's angles are read from the nodes' rotations as they are from the deck's form parameters.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from sim_solvers import Problem, Run, Solver


def exudyn_version() -> str:
    try:
        from importlib.metadata import version

        return version("exudyn")
    except Exception:  # noqa: BLE001
        return "not installed"


def rot(angle: float, u: float, v: float) -> tuple[float, float]:
    s, c = math.sin(angle), math.cos(angle)
    return u * c - v * s, u * s + v * c


class Planar:
    """A small builder: bodies by frame (origin, angle) and centre, joints by point, in SI units."""

    def __init__(self) -> None:
        import exudyn as exu

        self.exu = exu
        self.sc = exu.SystemContainer()
        self.mbs = self.sc.AddSystem()
        self.ground = self.mbs.AddObject(self._item("ObjectGround")())
        self.frames: list[tuple[int, int, tuple[float, float], float, tuple[float, float]]] = []

    @staticmethod
    def _item(name: str) -> Any:
        import exudyn.itemInterface as items

        return getattr(items, name)

    def body(self, origin: tuple[float, float], angle: float, com: tuple[float, float], m: float, j: float) -> int:
        """A rigid body whose frame has ``origin`` and ``angle``, its centre at ``com`` in that frame; its index."""
        cx, cy = (a + b for a, b in zip(origin, rot(angle, *com), strict=True))
        node = self.mbs.AddNode(self._item("NodeRigidBody2D")(referenceCoordinates=[cx, cy, angle]))
        obj = self.mbs.AddObject(self._item("ObjectRigidBody2D")(physicsMass=m, physicsInertia=j, nodeNumber=node))
        self.frames.append((node, obj, origin, angle, com))
        return len(self.frames) - 1

    def marker(self, body: int | None, point: tuple[float, float]) -> int:
        """A marker at the absolute point ``point`` (on the ground, or on ``body`` where it is at the start)."""
        if body is None:
            return self.mbs.AddMarker(
                self._item("MarkerBodyPosition")(bodyNumber=self.ground, localPosition=[*point, 0.0])
            )
        _, obj, origin, angle, com = self.frames[body]
        du, dv = rot(-angle, point[0] - origin[0], point[1] - origin[1])
        local = [du - com[0], dv - com[1], 0.0]
        return self.mbs.AddMarker(self._item("MarkerBodyPosition")(bodyNumber=obj, localPosition=local))

    def pin(self, a: int | None, b: int, point: tuple[float, float]) -> None:
        self.mbs.AddObject(
            self._item("ObjectJointRevolute2D")(markerNumbers=[self.marker(a, point), self.marker(b, point)])
        )

    def rotation_marker(self, body: int) -> int:
        return self.mbs.AddMarker(self._item("MarkerNodeCoordinate")(nodeNumber=self.frames[body][0], coordinate=2))

    def sensor(self, body: int, kind: str) -> int:
        out = getattr(self.exu.OutputVariableType, kind)
        return self.mbs.AddSensor(
            self._item("SensorNode")(nodeNumber=self.frames[body][0], storeInternal=True, outputVariableType=out)
        )


def andrews(problem: Problem) -> tuple[Any, list[int], Any]:
    """Andrews' squeezer: the model, its sensors (the seven bodies' rotations) and how to read the angles."""
    import andrews as a

    beta, theta, gamma, phi, delta, omega, eps = (float(x) for x in a.Q0)
    o, pa, pb, pc = (0.0, 0.0), (a.XA, a.YA), (a.XB, a.YB), (a.XC, a.YC)
    p = rot(beta, a.RR, 0.0)
    e = tuple(x + y for x, y in zip(p, rot(beta + theta, -a.D, 0.0), strict=True))
    d = tuple(x + y for x, y in zip(pb, rot(gamma, a.SD, -a.SC), strict=True))
    g = tuple(x + y for x, y in zip(pa, rot(delta, a.ZT, 0.0), strict=True))
    h = tuple(x + y for x, y in zip(pa, rot(eps, 0.0, -a.U), strict=True))
    m = Planar()
    crank = m.body(o, beta, (a.RA, 0.0), a.M[0], a.I[0])
    body2 = m.body(p, beta + theta + math.pi, (a.DA, 0.0), a.M[1], a.I[1])
    body3 = m.body(pb, gamma - math.pi / 2, (a.SA, a.SB), a.M[2], a.I[2])
    body5 = m.body(pa, delta, (a.TA, a.TB), a.M[4], a.I[4])
    body4 = m.body(g, phi + delta - math.pi / 2, (a.E - a.EA, 0.0), a.M[3], a.I[3])
    body7 = m.body(pa, eps - math.pi / 2, (a.UA, a.UB), a.M[6], a.I[6])
    body6 = m.body(h, omega + eps, (a.ZF - a.FA, 0.0), a.M[5], a.I[5])
    m.pin(None, crank, o)
    m.pin(crank, body2, p)
    m.pin(None, body3, pb)
    m.pin(body2, body3, e)
    m.pin(None, body5, pa)
    m.pin(body5, body4, g)
    m.pin(body2, body4, e)
    m.pin(None, body7, pa)
    m.pin(body7, body6, h)
    m.pin(body2, body6, e)
    spring = m._item("ObjectConnectorSpringDamper")
    m.mbs.AddObject(
        spring(markerNumbers=[m.marker(None, pc), m.marker(body3, d)], stiffness=a.C0, referenceLength=a.L0)
    )
    m.mbs.AddLoad(m._item("LoadCoordinate")(markerNumber=m.rotation_marker(crank), load=a.MOM))
    order = [crank, body2, body3, body4, body5, body6, body7]
    sensors = [m.sensor(b, "Coordinates") for b in order]
    ref = np.array([m.frames[b][3] for b in order])

    def read(columns: Any) -> Any:
        # columns: outputs x 7 rotations (displacements from the reference angles).
        r = columns + ref
        b1, b2, b3, b4, b5, b6, b7 = r.T
        return np.stack(
            [
                b1,
                b2 - b1 - math.pi,
                b3 + math.pi / 2,
                b4 - b5 + math.pi / 2,
                b5,
                b6 - (b7 + math.pi / 2),
                b7 + math.pi / 2,
            ],
            axis=1,
        )

    return m, sensors, read


def stiff_fourbar(problem: Problem) -> tuple[Any, list[int], Any]:
    """The stiff four-bar: the model, its sensors (the crank's rotation and its rate) and how to read them."""
    import stiff_fourbar as f

    phi, psi = f.angles(f.Q0)
    pa = rot(f.Q0, f.A, 0.0)
    pb = (pa[0] + f.B * math.cos(phi), pa[1] + f.B * math.sin(phi))
    pq = (f.XQ, 0.0)
    m = Planar()
    crank = m.body((0.0, 0.0), f.Q0, (f.A / 2, 0.0), f.M1, f.M1 * f.A**2 / 12)
    coupler = m.body(pa, phi, (f.B / 2, 0.0), f.M2, f.J2)
    rocker = m.body(pq, psi, (f.C / 2, 0.0), f.M3, f.M3 * f.C**2 / 12)
    m.pin(None, crank, (0.0, 0.0))
    m.pin(crank, coupler, pa)
    m.pin(coupler, rocker, pb)
    m.pin(None, rocker, pq)
    m.mbs.AddLoad(m._item("LoadCoordinate")(markerNumber=m.rotation_marker(crank), load=f.TORQUE))
    fixed = m.mbs.AddNode(m._item("NodePointGround")(referenceCoordinates=[0.0, 0.0, 0.0]))
    at_rest = m.mbs.AddMarker(m._item("MarkerNodeCoordinate")(nodeNumber=fixed, coordinate=0))
    spring = m._item("ObjectConnectorCoordinateSpringDamper")
    m.mbs.AddObject(
        spring(markerNumbers=[at_rest, m.rotation_marker(rocker)], stiffness=f.K, damping=f.DAMPING, offset=0.0)
    )
    sensors = [m.sensor(crank, "Coordinates"), m.sensor(crank, "Coordinates_t")]

    def read(columns: Any) -> Any:
        return np.stack([columns[:, 0] + f.Q0, columns[:, 1]], axis=1)

    return m, sensors, read


class Exudyn(Solver):
    """Exudyn's generalized-alpha (spectral radius 0.9, its default) with a fixed number of steps, Newton to 1e-12
    relative; the model built and assembled once, each run starting again from its initial values."""

    name = "Exudyn gen.-alpha"
    per_call_differs = True

    def build(self, problem: Problem) -> None:
        super().build(problem)
        assert problem.exudyn is not None
        self.model, self.sensors, self.read = problem.exudyn(problem)
        self.model.mbs.Assemble()

    def settings(self, steps: int) -> Any:
        exu = self.model.exu
        p = self.problem
        s = exu.SimulationSettings()
        s.timeIntegration.numberOfSteps = steps
        s.timeIntegration.endTime = float(p.times[-1])
        s.timeIntegration.verboseMode = 0
        s.timeIntegration.newton.relativeTolerance = 1e-12
        s.timeIntegration.newton.absoluteTolerance = 1e-14
        s.solutionSettings.writeSolutionToFile = False
        s.solutionSettings.sensorsWritePeriod = float(p.times[1] - p.times[0])
        s.displayStatistics = False
        s.displayComputationTime = False
        return s

    def run(self, steps: int) -> Run:
        return self._solve(self.model, self.sensors, self.read, steps)

    def run_fresh(self, steps: int) -> Run:
        model, sensors, read = self.problem.exudyn(self.problem)  # type: ignore[misc]
        model.mbs.Assemble()
        return self._solve(model, sensors, read, steps)

    def _solve(self, model: Any, sensors: list[int], read: Any, steps: int) -> Run:
        solver = model.exu.MainSolverImplicitSecondOrder()
        ok = solver.SolveSystem(model.mbs, self.settings(steps))
        newton = int(solver.it.newtonStepsCount)
        if not ok:
            return Run(None, newton, steps, int(solver.it.newtonJacobiCount), "did not converge")
        cols = []
        for s in sensors:
            data = np.asarray(model.mbs.GetSensorStoredData(s))
            cols.append(data[:, 3] if data.shape[1] > 3 else data[:, 1])
        values = np.stack(cols, axis=1)
        n = len(self.problem.times)
        if values.shape[0] != n:
            # The sensors write at their period; keep the rows at the output times.
            t = np.asarray(model.mbs.GetSensorStoredData(sensors[0]))[:, 0]
            idx = [int(np.argmin(np.abs(t - x))) for x in self.problem.times]
            values = values[idx]
        return Run(read(values), newton, steps, int(solver.it.newtonJacobiCount), "evaluations: Newton iterations")
