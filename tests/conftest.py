"""Shared fixtures: outputs go under tmp_path; the process works in a temporary folder so that
nothing (e.g. a MUJOCO_LOG.TXT) can land in the repository."""

import pytest

import sim_origami  # noqa: F401  (chooses the headless MUJOCO_GL before any test module imports mujoco)


@pytest.fixture(autouse=True)
def _work_in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
