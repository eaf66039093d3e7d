"""Disjoint sets (union-find) and Kruskal spanning forests: the one implementation every layer uses (no imports)."""

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
                   prefer: Iterable[int] = ()) -> list[int]:  # fmt: skip
    """
    Indices of the edges of a spanning forest, Kruskal in edge order with the edges in `prefer` taken first (so
    they are never left out unless they close a cycle among themselves). Sorted by index.
    """
    first = set(prefer)
    sets = DisjointSets(nodes)
    order = sorted(range(len(edges)), key=lambda i: (i not in first, i))
    return sorted(i for i in order if sets.union(*edges[i]))
