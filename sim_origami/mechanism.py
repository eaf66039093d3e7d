"""The mechanism graph: bodies, revolute joints, a spanning tree, loop closures and poses.

Frames. Every body has a frame; geometry is given in it. A joint carries one frame on each of its
two bodies (4x4, in that body's frame) whose z axis is the joint axis. The joint angle q is the
right-handed rotation about that axis of `child` relative to `parent`:

    T_child = T_parent @ frame_parent @ Rz(q) @ inv(frame_child).

For an origami vertex every body frame is the world frame of the flat sheet, both joint frames
lie on the crease with z = +d_i, `parent` is the clockwise panel and `child` the counter-clockwise
one, so q is the fold angle rho of `sim_origami.conventions`.

A breadth-first spanning tree from the root body (fixed to the world) keeps the joints that must
be driven or coupled; every other joint is cut and becomes a loop closure. A coupling
(joint, other, scale) imposes q_joint = scale * q_other (a symmetry the model assumes, or the
periodic copy of a crease outside a unit cell); both joints must be in the tree. A cut joint in `implied`
is a loop the couplings and the other closures already close (`implied_cuts`): the MJCF measures it but does
not impose it, which removes redundant constraint rows (the waterbomb tube's symmetry makes most of them so).
"""

from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from .closure import Coupling, Loop, LoopSystem
from .errors import ParameterError
from .geometry import invert, transform_z, xyz_angles
from .graph import spanning_edges

# A loop is implied when its leftover closure rows (past the span of the couplings and the kept loops) are below
# IMPLIED_RTOL of their size. Measured on the waterbomb tube and twist: see `implied_cuts`' callers (scenes.base).
IMPLIED_RTOL = 1e-9


def _orthonormal_rows(A: NDArray[np.float64], tol: float) -> NDArray[np.float64]:
    """Orthonormal rows spanning the rows of A (singular values above tol; absolute when A is a leftover)."""
    if not len(A):
        return np.zeros((0, A.shape[1]))
    _, s, Vt = np.linalg.svd(A, full_matrices=False)
    return Vt[s > tol]


@dataclass(frozen=True)
class Body:
    """
    A rigid panel or link; `solid` and `collision` are meshes in the body frame.

    A `spacer` has no geometry and no mass: it only carries one axis of a spherical joint (see `ball_joint`).
    """

    name: str
    solid: trimesh.Trimesh
    collision: trimesh.Trimesh | None = None
    rgba: tuple[float, float, float, float] = (0.8, 0.8, 0.8, 1.0)
    spacer: bool = False


@dataclass(frozen=True)
class Joint:
    """
    A revolute joint; `anchors` are points along its z axis where a cut joint is closed.

    `ball` names the spherical joint this hinge is one axis of ("" for a plain hinge; see `ball_joint`).
    """

    name: str
    parent: str
    child: str
    frame_parent: NDArray[np.float64]
    frame_child: NDArray[np.float64]
    anchors: tuple[float, ...] = (0.5, 1.0)
    ball: str = ""


# The hinge axes of a spherical joint in its triad frame: x, then y, then z (intrinsic X-Y-Z angles).
_TRIAD_AXES = (
    np.array([[0.0, 0, 1, 0], [0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 0, 1]]),  # z -> x
    np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]]),  # z -> y
    np.eye(4),
)


def ball_joint(
    name: str, parent: str, child: str, frame_parent: ArrayLike, frame_child: ArrayLike
) -> tuple[tuple[Body, Body], tuple[Joint, Joint, Joint]]:
    """
    A spherical joint as three concurrent hinges through its centre, for the loop algebra.

    `frame_parent` / `frame_child` (4, 4) are the joint's triad frame (origin at the centre) in each body's
    frame; they coincide in the reference pose. The hinges `<name>_x`, `<name>_y`, `<name>_z` turn about the
    triad's x, then the (turned) y, then z, through two spacer bodies `<name>_g1`, `<name>_g2`, so

        T_child = T_parent @ frame_parent @ Rx(a) @ Ry(b) @ Rz(c) @ inv(frame_child)

    with (a, b, c) the three hinge angles (rad). The angles are singular at b = +-pi/2 (choose the triad so
    the motion stays clear of it). MJCF writes the group as one MuJoCo ball joint when it is in the spanning
    tree, or as one `connect` at the centre when its last hinge is cut.
    """
    Fp, Fc = np.asarray(frame_parent, dtype=float), np.asarray(frame_child, dtype=float)
    chain = [parent, f"{name}_g1", f"{name}_g2", child]
    spacers = tuple(Body(b, trimesh.Trimesh(), None, spacer=True) for b in chain[1:3])
    outer = (Fp, np.eye(4), np.eye(4)), (np.eye(4), np.eye(4), Fc)
    joints = tuple(
        Joint(f"{name}_{'xyz'[k]}", chain[k], chain[k + 1], outer[0][k] @ A, outer[1][k] @ A, (0.0,), name)
        for k, A in enumerate(_TRIAD_AXES)
    )
    return spacers, joints


@dataclass(frozen=True)
class TreeEdge:
    """A tree joint as traversed from `parent` body to `child` body; `sign` -1 when reversed."""

    joint: int
    parent: str
    child: str
    sign: int


@dataclass(frozen=True)
class Mechanism:
    """
    Bodies and joints; `root` is fixed to the world, joints in `keep` and in couplings stay in the tree;
    `breadth_first` picks a shortest-path spanning tree from the root (else Kruskal in joint order); `implied`
    names cut hinges whose closure is measured but not imposed (see `implied_cuts`).
    """

    bodies: tuple[Body, ...]
    joints: tuple[Joint, ...]
    root: str
    keep: tuple[str, ...] = field(default=())
    couplings: tuple[tuple[str, str, float], ...] = field(default=())
    breadth_first: bool = False
    implied: tuple[str, ...] = field(default=())

    def __post_init__(self):
        names = [b.name for b in self.bodies]
        if self.root not in names:
            raise ParameterError(f"root body {self.root!r} is not one of {names}")
        for j in self.joints:
            for b in (j.parent, j.child):
                if b not in names:
                    raise ParameterError(f"joint {j.name!r} names unknown body {b!r}")
        tree = self.tree_joint_names() if self.couplings else set()
        for joint, other, _ in self.couplings:
            for name in (joint, other):
                self.joint_index(name)
                if name not in tree:
                    raise ParameterError(
                        f"coupled joint {name!r} was cut to close a loop; couplings need joints of the spanning tree"
                    )
        cut = {self.joints[i].name for i in self.cut_joints if not self.joints[i].ball} if self.implied else set()
        for name in self.implied:
            if name not in cut:
                raise ParameterError(f"implied closure {name!r} is not a cut hinge; cut hinges are {sorted(cut)}")

    @cached_property
    def length_scale(self) -> float:
        """The largest dimension of any body's solid (m): the size length tolerances are relative to."""
        return max((float(np.max(b.solid.extents)) for b in self.bodies if len(b.solid.vertices)), default=1.0) or 1.0

    def joint_index(self, name: str) -> int:
        """Position of joint `name` in `joints`."""
        try:
            return self._joint_indices[name]
        except KeyError:
            raise ParameterError(f"unknown joint {name!r}; joints are {[j.name for j in self.joints]}") from None

    @cached_property
    def _joint_indices(self) -> dict[str, int]:
        """Joint name -> its position (the first, as a linear search would find it): 3362 look-ups of a 480-crease
        pattern's validation took 0.1 s one by one."""
        out: dict[str, int] = {}
        for i, j in enumerate(self.joints):
            out.setdefault(j.name, i)
        return out

    @cached_property
    def tree(self) -> tuple[TreeEdge, ...]:
        """
        Spanning-tree edges in breadth-first order from the root.

        Joints are taken Kruskal-style, those in `keep` or a coupling first, so they are not cut, then in
        joint order or (`breadth_first`) nearest the root first; the chosen joints are oriented breadth-first
        from the root.
        """
        names = [b.name for b in self.bodies]
        wanted = set(self.keep) | {name for c in self.couplings for name in c[:2]}
        wanted |= {j.name for j in self.joints if j.ball and not j.name.endswith("_z")}  # a ball cuts at its last
        prefer = [i for i, j in enumerate(self.joints) if j.name in wanted]
        root = self.root if self.breadth_first else None
        chosen = spanning_edges(names, [(j.parent, j.child) for j in self.joints], prefer, root)  # sorted
        # each body's chosen joints in joint order, listed once (scanning them all for every body took 1.0 s on a
        # pattern of 2500 panels)
        incident: dict[str, list[int]] = {}
        for i in chosen:
            for b in dict.fromkeys((self.joints[i].parent, self.joints[i].child)):
                incident.setdefault(b, []).append(i)
        seen, edges, queue = {self.root}, [], deque([self.root])
        while queue:
            body = queue.popleft()
            for i in incident.get(body, ()):
                j = self.joints[i]
                other, sign = (j.child, 1) if j.parent == body else (j.parent, -1)
                if other not in seen:
                    seen.add(other)
                    edges.append(TreeEdge(i, body, other, sign))
                    queue.append(other)
        missing = set(names) - seen
        if missing:
            raise ParameterError(f"bodies {sorted(missing)} are not connected to root {self.root!r}")
        return tuple(edges)

    def tree_joint_names(self) -> set[str]:
        """Names of the joints kept in the spanning tree."""
        return {self.joints[e.joint].name for e in self.tree}

    @cached_property
    def cut_joints(self) -> tuple[int, ...]:
        """Joints not in the tree: one loop closure each."""
        tree = {e.joint for e in self.tree}
        return tuple(i for i in range(len(self.joints)) if i not in tree)

    def _step(self, i: int, from_body: str) -> tuple[NDArray, int, NDArray]:
        """(F_from, sign, F_to) so that T_to = T_from @ F_from @ Rz(sign q_i) @ inv(F_to)."""
        j = self.joints[i]
        if from_body == j.parent:
            return j.frame_parent, 1, j.frame_child
        return j.frame_child, -1, j.frame_parent

    def body_poses(self, q: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """World poses (..., 4, 4) of every body for joint angles q (..., n_joints); cut joints unused."""
        q = np.asarray(q, dtype=float)
        poses = {self.root: np.broadcast_to(np.eye(4), (*q.shape[:-1], 4, 4))}
        for e in self.tree:
            F_from, sign, F_to = self._step(e.joint, e.parent)
            poses[e.child] = poses[e.parent] @ F_from @ transform_z(sign * q[..., e.joint]) @ invert(F_to)
        return poses

    def hinge_mismatch(self, q: ArrayLike, joints: Iterable[str]) -> float:
        """
        Largest entry of |inv(T_parent F_p) T_child F_c - Rz(q_i)| over the named hinges, with the body poses of
        the tree at angles q (..., n_joints): 0 when each of those hinges (cut ones included) turns by its angle.
        """
        q = np.asarray(q, dtype=float)
        poses, worst = self.body_poses(q), 0.0
        for name in joints:
            i = self.joint_index(name)
            j = self.joints[i]
            turn = invert(poses[j.parent] @ j.frame_parent) @ poses[j.child] @ j.frame_child
            worst = max(worst, float(np.max(np.abs(turn - transform_z(q[..., i])))))
        return worst

    def reference_poses(self) -> dict[str, NDArray[np.float64]]:
        """Body poses at q = 0 (the reference pose of the MJCF model)."""
        return self.body_poses(np.zeros(len(self.joints)))

    def complete(self, q: ArrayLike) -> NDArray[np.float64]:
        """
        Fill in cut-joint angles measured from the tree pose, (..., n_joints).

        A cut joint's angle is the z rotation of inv(F_p) inv(T_parent) T_child F_c, which is
        exactly Rz(q) when the loop is closed. A spherical joint whose last hinge is cut is measured
        whole (its three angles) from the poses of its two end bodies.
        """
        q = np.array(q, dtype=float)
        poses = self.body_poses(q)
        cut = set(self.cut_joints)
        for name, (ix, iy, iz) in self.balls.items():
            if iz in cut:
                ends = poses[self.joints[ix].parent], poses[self.joints[iz].child]
                q[..., [ix, iy, iz]] = self.ball_angles(name, *ends)
        for i in cut:
            j = self.joints[i]
            if not j.ball:
                M = invert(j.frame_parent) @ invert(poses[j.parent]) @ poses[j.child] @ j.frame_child
                q[..., i] = np.arctan2(M[..., 1, 0], M[..., 0, 0])
        return q

    @cached_property
    def balls(self) -> dict[str, tuple[int, int, int]]:
        """Each spherical joint's name and the indices of its x, y, z hinges (see `ball_joint`)."""
        return {j.name[:-2]: tuple(self.joint_index(j.name[:-1] + a) for a in "xyz") for j in self.joints
                if j.ball and j.name.endswith("_x")}

    @cached_property
    def idle_spins(self) -> int:
        """
        Bodies held only by two spherical joints (S-S bars): each spins freely about the line through the two
        centres, a trivial mode that loop ranks and MuJoCo count and the truss method does not (Yang 2017, §2.2).
        """
        ends: dict[str, list[str]] = {}
        for j in self.joints:
            if not (j.ball and j.name.endswith(("_x", "_z"))):
                for body in (j.parent, j.child):
                    ends.setdefault(body, []).append("hinge")
            else:
                ends.setdefault(j.parent if j.name.endswith("_x") else j.child, []).append("ball")
        spacers = {b.name for b in self.bodies if b.spacer}
        return sum(kinds == ["ball", "ball"] for body, kinds in ends.items() if body not in spacers)

    def ball_frames(self, name: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Triad frames (4, 4) of spherical joint `name` in its parent's and its child's body frames."""
        ix, _, iz = self.balls[name]
        return self.joints[ix].frame_parent @ _TRIAD_AXES[0].T, self.joints[iz].frame_child

    def ball_angles(self, name: str, T_parent: ArrayLike, T_child: ArrayLike) -> NDArray[np.float64]:
        """
        Angles (..., 3) (rad) of spherical joint `name` between world poses (..., 4, 4) of its end bodies:
        the intrinsic x-y-z angles of the child's turn relative to the parent in the joint's triad.
        """
        Fp, Fc = self.ball_frames(name)
        return xyz_angles((invert(Fp) @ invert(np.asarray(T_parent)) @ np.asarray(T_child) @ Fc)[..., :3, :3])

    def reduced(self) -> "Mechanism":
        """
        This mechanism with each spherical joint as one Joint named after it between its end bodies (frames =
        its triad frames, anchor at the centre) and no spacers: the graph the truss method reads. Its angles
        for those joints are meaningless (`body_poses` of the reduced graph treats them as hinges).
        """
        joints = [j for j in self.joints if not j.ball]
        for name, (ix, _, iz) in self.balls.items():
            joints.append(Joint(name, self.joints[ix].parent, self.joints[iz].child, *self.ball_frames(name), (0.0,)))
        bodies = tuple(b for b in self.bodies if not b.spacer)
        return Mechanism(bodies, tuple(joints), self.root, self.keep, self.couplings, self.breadth_first)

    def angles_from_poses(self, poses: dict[str, ArrayLike]) -> NDArray[np.float64]:
        """
        Every joint angle (n, n_joints) (rad) from world poses (n, 4, 4) of every non-spacer body,
        e.g. a closed form's: hinges as in `complete`, spherical joints by `ball_angles`.
        """
        poses = {k: np.asarray(v, dtype=float).reshape(-1, 4, 4) for k, v in poses.items()}
        n = len(next(iter(poses.values())))
        q = np.zeros((n, len(self.joints)))
        for name, (ix, iy, iz) in self.balls.items():
            q[:, [ix, iy, iz]] = self.ball_angles(name, poses[self.joints[ix].parent], poses[self.joints[iz].child])
        for i, j in enumerate(self.joints):
            if not j.ball:
                M = invert(j.frame_parent) @ invert(poses[j.parent]) @ poses[j.child] @ j.frame_child
                q[:, i] = np.arctan2(M[:, 1, 0], M[:, 0, 0])
        return q

    def loop_system(self) -> LoopSystem:
        """Each cut joint with its tree path, as a closed chain (see `closure`)."""
        parent_of = {e.child: e for e in self.tree}

        def path_to_root(body: str) -> list[str]:
            out = [body]
            while out[-1] != self.root:
                out.append(parent_of[out[-1]].parent)
            return out

        loops = []
        for c in self.cut_joints:
            j = self.joints[c]
            up, down = path_to_root(j.child), path_to_root(j.parent)
            common = next(b for b in up if b in down)
            # cycle: child -> ... -> common -> ... -> parent -> (cut joint) -> child
            steps = []
            for b in up[: up.index(common)]:
                steps.append((parent_of[b].joint, b))
            for b in reversed(down[: down.index(common)]):
                steps.append((parent_of[b].joint, parent_of[b].parent))
            steps.append((c, j.parent))
            factors = [self._step(i, frm) for i, frm in steps]
            links = [invert(factors[k][2]) @ factors[(k + 1) % len(factors)][0] for k in range(len(factors))]
            loops.append(Loop(tuple(i for i, _ in steps), np.array(links), tuple(f[1] for f in factors)))
        couplings = tuple(Coupling(self.joint_index(a), self.joint_index(b), scale) for a, b, scale in self.couplings)
        return LoopSystem(len(self.joints), tuple(loops), couplings)

    def implied_cuts(self, q: ArrayLike, rtol: float = IMPLIED_RTOL) -> tuple[str, ...]:
        """
        Cut hinges whose loop closure the couplings and the loops kept before them imply at every pose of q
        (k, n_joints) (rad): the closures left out of a model without changing what it can do there.

        Loops are taken in cut-joint order. A loop's six closure-Jacobian rows, combined so that the cut joint's
        own columns vanish (MuJoCo has no coordinate for them: a cut hinge's connects leave its angle free, a cut
        spherical joint's connect all three), constrain the tree's joints; the loop is implied when those rows lie
        in the span of the couplings' and the kept loops' rows at every pose (leftover singular values <= rtol
        times the rows' largest). Loops cut at spherical joints are always kept. Sample poses on every branch,
        ends and bifurcations included, so that no pose leans on a loop left out.
        """
        q = np.atleast_2d(np.asarray(q, dtype=float))
        system = self.loop_system()
        jacobians = [system.jacobian(pose) for pose in q]
        n_loops = len(system.loops)
        bases = [_orthonormal_rows(J[6 * n_loops :], rtol) for J in jacobians]
        implied = []
        for m, c in enumerate(self.cut_joints):
            joint = self.joints[c]
            own = list(self.balls[joint.ball]) if joint.ball else [c]
            leftovers = []
            for J, basis in zip(jacobians, bases, strict=True):
                rows = J[6 * m : 6 * m + 6]
                U, s, _ = np.linalg.svd(rows[:, own])
                rows = U[:, int(np.sum(s > rtol * max(s[0], 1.0))) :].T @ rows  # left null space of own columns
                leftovers.append((rows - (rows @ basis.T) @ basis, np.linalg.norm(rows, 2)))
            if not joint.ball and all(np.linalg.norm(r, 2) <= rtol * scale for r, scale in leftovers):
                implied.append(joint.name)
                continue
            bases = [np.vstack([basis, _orthonormal_rows(r, rtol * scale)])
                     for basis, (r, scale) in zip(bases, leftovers, strict=True)]
        return tuple(implied)

    def uncoupled(self) -> "Mechanism":
        """This mechanism without its couplings, every loop closed (the closures they implied no longer are)."""
        return replace(self, couplings=(), implied=())

    def anchor_points(self, i: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Closure anchor points (k, 3) of joint i in its parent's and its child's body frames."""
        j = self.joints[i]
        local = np.array([[0.0, 0.0, s, 1.0] for s in j.anchors])
        return (local @ j.frame_parent.T)[:, :3], (local @ j.frame_child.T)[:, :3]
