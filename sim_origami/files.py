"""
Atomic output: every file is written under a temporary name in its folder, then renamed. A run claims its output
folder (`claimed_folder`): checked before any work, cleaned of an earlier run's files, recorded in a manifest.
"""

import contextlib
import json
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

from .errors import ParameterError


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """
    Yield a temporary path beside `path` (same suffix, so writers can tell the format); on
    success it replaces `path`, on error it is removed and `path` is left as it was.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.", suffix=path.suffix)
    os.close(fd)
    os.chmod(tmp, 0o644)  # mkstemp creates 0600; outputs are ordinary files
    try:
        yield Path(tmp)
        _record(path)  # listed before it appears, so an interrupted run's file is still removed by the next run
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write text atomically; returns the path."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


# A run's record of the files it wrote into its output folder (relative paths), and the lock a running run holds.
MANIFEST = ".sim_origami-run.json"
LOCK = ".sim_origami-run.lock"
# Output folders claimed by this process: folder -> files written so far (relative to it).
_CLAIMED: dict[Path, list[str]] = {}


def check_folder(path: str | os.PathLike, option: str = "--out", *, make: bool = True) -> Path:
    """
    The output folder `path`, created if missing (unless not `make`), after checking it can be written:
    ParameterError (one line naming the path and the problem) when it is a file, lies under a file, or it or its
    nearest existing parent cannot be written. Called before any work starts.
    """
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ParameterError(f"{option} {path}: it is a file, not a folder")
    parent = path
    while not parent.exists():
        if parent.is_symlink():  # a dangling link
            raise ParameterError(f"{option} {path}: {parent} is a broken link")
        parent = parent.parent
    if not parent.is_dir():
        raise ParameterError(f"{option} {path}: {parent} is a file, so no folder can be made under it")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise ParameterError(f"{option} {path}: {parent} is not writable")
    if not make:
        return path
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ParameterError(f"{option} {path}: the folder cannot be made ({exc.strerror})") from None
    return path


@contextlib.contextmanager
def claimed_folder(path: str | os.PathLike, *, force: bool = False, option: str = "--out") -> Iterator[Path]:
    """
    Own the output folder `path` for one run (`check_folder` first). A run owns what it writes: the files an earlier
    run of this tool wrote there (listed in its MANIFEST) are removed first, so reports, frames and movies of two
    runs never mix; a folder holding other files is refused unless `force` (they are then left alone); a folder
    another live run holds (LOCK) is refused. Every file written through `atomic_path` inside it is recorded in the
    manifest as it is written, so an interrupted run is cleaned up by the next one.
    """
    path = check_folder(path, option).resolve()
    lock = path / LOCK
    try:
        fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
    except FileExistsError:
        holder = _lock_holder(lock)
        if holder is not None:
            raise ParameterError(f"{option} {path}: another run (process {holder}) is writing there") from None
        lock.unlink(missing_ok=True)  # left by a run that died
        fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
    os.write(fd, str(os.getpid()).encode())
    os.close(fd)
    try:
        _remove_earlier_run(path)
        foreign = sorted(p.name for p in path.iterdir() if p.name not in (LOCK, MANIFEST) and not _is_run(p))
        if foreign and not force:
            raise ParameterError(
                f"{option} {path}: the folder holds files this tool did not write ({', '.join(foreign[:3])}"
                f"{', ...' if len(foreign) > 3 else ''}); give an empty folder, or --force to write beside them"
            )
        _CLAIMED[path] = []
        _write_manifest(path)
        yield path
    finally:
        _CLAIMED.pop(path, None)
        lock.unlink(missing_ok=True)


def _lock_holder(lock: Path) -> int | None:
    """The live process holding `lock`, None when the lock is stale (its process is gone) or unreadable."""
    try:
        pid = int(lock.read_text().strip() or 0)
        os.kill(pid, 0)
    except (ValueError, OSError):
        return None
    return pid


def _is_run(entry: Path) -> bool:
    """A sub-folder that is itself a run's output folder (validate --all writes one per scene)."""
    return entry.is_dir() and (entry / MANIFEST).exists()


def _remove_earlier_run(path: Path) -> None:
    """Remove the files the manifest in `path` lists, then folders they leave empty, then the manifest."""
    manifest = path / MANIFEST
    if not manifest.exists():
        return
    try:
        files = json.loads(manifest.read_text()).get("files", [])
    except (ValueError, AttributeError):
        raise ParameterError(f"--out {path}: {MANIFEST} is not a run manifest; remove it or pick another folder") \
            from None
    folders = set()
    for name in files:
        target = (path / name).resolve()
        if path in target.parents:  # never outside the folder, whatever the manifest says
            target.unlink(missing_ok=True)
            folders.update(p for p in target.parents if path in p.parents)
    for folder in sorted(folders, key=lambda p: len(p.parts), reverse=True):
        with contextlib.suppress(OSError):
            folder.rmdir()  # only when empty
    manifest.unlink()


def _write_manifest(path: Path) -> None:
    doc = {"tool": "sim_origami", "pid": os.getpid(), "files": _CLAIMED[path]}
    tmp = path / f".{MANIFEST}.{os.getpid()}.tmp"
    try:
        tmp.write_text(json.dumps(doc, indent=1) + "\n")
        os.replace(tmp, path / MANIFEST)
    except BaseException:  # a signal between the two (raised as Interrupted) left the temporary file behind in CI
        tmp.unlink(missing_ok=True)
        raise


def _record(path: Path) -> None:
    """Add a written file to the manifest of the innermost claimed folder holding it, if any."""
    path = path.resolve()
    holders = [folder for folder in _CLAIMED if folder in path.parents]
    if not holders:
        return
    folder = max(holders, key=lambda f: len(f.parts))
    name = str(path.relative_to(folder))
    if name not in _CLAIMED[folder]:
        _CLAIMED[folder].append(name)
        _write_manifest(folder)


def write_or_check(path: str | os.PathLike, text: str, check: bool, how: str) -> int:
    """
    A generated page: with `check`, 0 if `path` holds `text` and 1 (saying `how` to regenerate it) if not; else
    write it. Returns an exit status for the generating script.
    """
    path = Path(path)
    if check:
        if not path.exists() or path.read_text() != text:
            print(f"{path} is not current: run {how}", file=sys.stderr)
            return 1
        return 0
    write_text(path, text)
    print(f"wrote {path}")
    return 0
