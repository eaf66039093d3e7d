"""Disjoint sets (union-find), Kruskal spanning forests and a graph's centre: the one implementation every layer
uses (no imports)."""

from collections import deque
from collections.abc import Hashable, Iterable, Sequence


class DisjointSets:
    """Union-find over hashable, mutually ordered items; a set's root is its smallest item."""

    def __init__(self, items: Iterable[Hashable]):
        self.parent = {x: x for x in items}

    def find(self, x: Hashable) -> Hashable:
        """The root of x's set (with path halving)."""
        parent = self.parent
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    def union(self, a: Hashable, b: Hashable) -> bool:
        """Merge the sets of a and b; False if they were one set already."""
        ra, rb = self.find(a), self.find(b)
        if ra == rb:
            return False
        if rb < ra:
            ra, rb = rb, ra
        self.parent[rb] = ra
        return True


def spanning_edges(nodes: Iterable[Hashable], edges: Sequence[tuple[Hashable, Hashable]],
                   prefer: Iterable[int] = (), root: Hashable | None = None) -> list[int]:
    """
    Indices of the edges of a spanning forest, Kruskal in edge order with the edges in `prefer` taken first (so
    they are never left out unless they close a cycle among themselves). Sorted by index.

    With a `root`, the other edges go in order of their nearer end's breadth-first depth from it: a shortest-path
    tree, as shallow as the graph allows (short loops through the tree).
    """
    nodes = list(nodes)
    first = set(prefer)
    depth = breadth_first_depths(nodes, edges, root) if root is not None else {}
    sets = DisjointSets(nodes)

    def rank(i: int) -> tuple:
        near = min(depth.get(edges[i][0], 0), depth.get(edges[i][1], 0))
        return (i not in first, near, i)

    return sorted(i for i in sorted(range(len(edges)), key=rank) if sets.union(*edges[i]))


def breadth_first_depths(
    nodes: Iterable[Hashable], edges: Sequence[tuple[Hashable, Hashable]], root: Hashable
) -> dict[Hashable, int]:
    """Edge count of the shortest path from `root` to every node it reaches."""
    return _depths(_neighbours(nodes, edges), root)


def _neighbours(nodes: Iterable[Hashable], edges: Sequence[tuple[Hashable, Hashable]]) -> dict[Hashable, list]:
    """Each node's neighbours, an edge's ends each other's."""
    neighbours: dict[Hashable, list[Hashable]] = {n: [] for n in nodes}
    for a, b in edges:
        neighbours[a].append(b)
        neighbours[b].append(a)
    return neighbours


def _depths(neighbours: dict[Hashable, list], root: Hashable) -> dict[Hashable, int]:
    """`breadth_first_depths` on a built neighbour map."""
    depth, queue = {root: 0}, deque([root])
    while queue:
        n = queue.popleft()
        for m in neighbours[n]:
            if m not in depth:
                depth[m] = depth[n] + 1
                queue.append(m)
    return depth


def central_node(nodes: Sequence[Hashable], edges: Sequence[tuple[Hashable, Hashable]], sweeps: int = 16) -> Hashable:
    """
    A node of least eccentricity (longest shortest path to any other) in the first node's component: a root for
    the shallowest breadth-first tree. Lower bounds from breadth-first sweeps: each sweep from an extreme node e
    bounds every node's eccentricity below by its distance to e; the candidate of least bound is swept, and is
    the answer when its eccentricity meets its bound (no node can do better), else the node farthest from it is
    the next extreme. Exact within `sweeps` (a grid takes its corners), else the least eccentric candidate seen.
    Ties go to the earlier node.
    """
    nodes = list(nodes)
    order = {n: k for k, n in enumerate(nodes)}
    neighbours = _neighbours(nodes, edges)  # built once for every sweep

    def farthest(depth: dict[Hashable, int]) -> Hashable:
        return max(depth, key=lambda n: (depth[n], -order[n]))

    bound = _depths(neighbours, nodes[0])
    extreme, best, best_ecc = farthest(bound), nodes[0], max(bound.values())
    bound = dict.fromkeys(bound, 0)
    for _ in range(sweeps):
        depth = _depths(neighbours, extreme)
        bound = {n: max(b, depth[n]) for n, b in bound.items()}
        candidate = min(bound, key=lambda n: (bound[n], order[n]))
        depth = _depths(neighbours, candidate)
        eccentricity = max(depth.values())
        if (eccentricity, order[candidate]) < (best_ecc, order[best]):
            best, best_ecc = candidate, eccentricity
        if eccentricity == bound[candidate]:
            break
        extreme = farthest(depth)
    return best
