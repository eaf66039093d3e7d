#!/usr/bin/env node
// Folds every frame of a FOLD file with Rabbit Ear, an independent FOLD reader (npm package rabbit-ear).
// Usage: node fold_frames.js FILE.fold
// Prints JSON {"frames": [frame 0 (the key frame), file_frames[0], ...]}, each frame the folded
// vertices_coords (n_vertices x 3) that Rabbit Ear computes from the frame's edges_foldAngle and
// edges_assignment (ear.graph.makeVerticesCoordsFolded, face 0 held fixed).
"use strict";
const fs = require("fs");
const path = require("path");
const ear = require("rabbit-ear");

// Frame k (0: the key frame) with what it inherits (FOLD 1.2: frame_inherit, frame_parent).
function resolve(doc, k) {
  const key = Object.fromEntries(Object.entries(doc).filter(([name]) => !name.startsWith("file_")));
  if (k === 0) return key;
  const frame = doc.file_frames[k - 1];
  if (frame.frame_inherit !== true) return frame;
  return { ...resolve(doc, frame.frame_parent ?? 0), ...frame };
}

// The installed rabbit-ear's version (its package.json is not in the package's exports).
function version() {
  const file = path.join(path.dirname(require.resolve("rabbit-ear")), "package.json");
  return JSON.parse(fs.readFileSync(file, "utf8")).version;
}

const doc = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
const count = 1 + (doc.file_frames || []).length;
const frames = [];
for (let k = 0; k < count; k += 1) {
  const frame = resolve(doc, k);
  const graph = {
    vertices_coords: frame.vertices_coords,
    edges_vertices: frame.edges_vertices,
    edges_assignment: frame.edges_assignment,
    edges_foldAngle: frame.edges_foldAngle,
    faces_vertices: frame.faces_vertices,
  };
  graph.faces_faces = ear.graph.makeFacesFaces(graph);
  frames.push(ear.graph.makeVerticesCoordsFolded(graph, 0));
}
process.stdout.write(JSON.stringify({ rabbit_ear: version(), frames }) + "\n");
