"""Union-find and Kruskal spanning forests (`sim_origami.graph`), shared by the mechanism tree, crease patterns and
the truss builder."""

import random

from sim_origami.graph import DisjointSets, breadth_first_depths, central_node, spanning_edges


def test_disjoint_sets_merge_once_and_keep_the_smallest_item_as_root():
    sets = DisjointSets(range(5))
    assert sets.union(3, 1) and sets.union(4, 3) and not sets.union(1, 4)
    assert {sets.find(k) for k in (1, 3, 4)} == {1} and sets.find(2) == 2


def test_spanning_edges_take_preferred_edges_first_and_skip_cycles():
    square = [("a", "b"), ("b", "c"), ("c", "d"), ("d", "a")]
    assert spanning_edges("abcd", square) == [0, 1, 2]
    assert spanning_edges("abcd", square, prefer=[3]) == [0, 1, 3]  # the preferred edge stays, another is cut
    assert spanning_edges("abcde", square) == [0, 1, 2]  # a forest: e stays alone


def test_spanning_edges_from_a_root_give_a_shortest_path_tree():
    ring = [(k, (k + 1) % 6) for k in range(6)]  # a hexagon: Kruskal in edge order keeps the path 0-1-2-3-4-5
    assert spanning_edges(range(6), ring) == [0, 1, 2, 3, 4]
    assert max(breadth_first_depths(range(6), ring[:5], 0).values()) == 5
    tree = spanning_edges(range(6), ring, root=0)  # from 0: an edge at the far node 3 is cut
    assert tree == [0, 1, 2, 4, 5]
    assert max(breadth_first_depths(range(6), [ring[i] for i in tree], 0).values()) == 3
    assert spanning_edges(range(6), ring, prefer=[3], root=0) == [0, 1, 3, 4, 5]  # a preferred edge still stays


def _eccentricity(nodes, edges, node):
    return max(breadth_first_depths(nodes, edges, node).values())


def test_the_central_node_of_a_grid_is_its_middle_not_a_far_corner_of_its_diagonal():
    """A double sweep (a far node, the node farthest from it, the middle between) ties a grid's anti-diagonal,
    corners included (eccentricity 30 on 16 x 16); the sweeps from the other corners single out the middle (16)."""
    n = 16
    nodes = [(i, j) for i in range(n) for j in range(n)]
    edges = [((i, j), (i + 1, j)) for i in range(n - 1) for j in range(n)]
    edges += [((i, j), (i, j + 1)) for i in range(n) for j in range(n - 1)]
    assert central_node(nodes, edges) == (7, 7) and _eccentricity(nodes, edges, (7, 7)) == 16


def test_the_central_node_has_the_least_eccentricity_of_any_node():
    """Exact on 200 random connected graphs (a random tree plus random chords), against every node's eccentricity."""
    rng = random.Random(1)
    for _ in range(200):
        nodes = list(range(rng.randint(1, 40)))
        edges = [(k, rng.randrange(k)) for k in nodes[1:]]
        edges += [tuple(rng.sample(nodes, 2)) for _ in range(rng.randint(0, len(nodes) if len(nodes) > 1 else 0))]
        assert _eccentricity(nodes, edges, central_node(nodes, edges)) == min(
            _eccentricity(nodes, edges, v) for v in nodes
        )
