"""
Atomic output and output folders. Every file is written under a temporary name in its folder, then renamed. A run
claims its output folder (`claimed_folder`) once its arguments are checked, writes into a staging folder inside it
and, when it finishes, swaps its files in for the previous run's: a refused, failed or interrupted run leaves the
previous results whole. A manifest records each file's sha256, so only files this tool wrote, unchanged, are removed.
"""

import contextlib
import hashlib
import json
import os
import shutil
import signal
import sys
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

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
        os.replace(tmp, path)
        _record(path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write text atomically; returns the path."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


# A run's record of the files it wrote into its output folder (relative paths and their sha256), the lock a running
# run holds, and the folder inside it where a run writes until it finishes.
MANIFEST = ".sim_origami-run.json"
LOCK = ".sim_origami-run.lock"
STAGING = ".sim_origami-staging"
# The manifest's layout: 2 added the sha256 of each file (1, a bare list, cannot tell a changed file from ours).
MANIFEST_VERSION = 2


@dataclass
class _Claim:
    """One claimed output folder: where the run writes, the previous run's files, files written in place."""

    folder: Path
    staging: Path
    previous: dict[str, str]
    option: str
    in_place: list[str] = field(default_factory=list)


# Output folders claimed by this process.
_CLAIMED: dict[Path, _Claim] = {}


def check_folder(path: str | os.PathLike, option: str = "--out", *, make: bool = True) -> Path:
    """
    The output folder `path`, created if missing (unless not `make`), after checking it can be written:
    ParameterError (one line naming the path and the problem) when it is a file, lies under a file, its name is
    too long, or it or its nearest existing parent cannot be written. Called before any work starts.
    """
    try:
        return _check_folder(Path(path), option, make)
    except OSError as exc:  # e.g. a name longer than the file system allows
        raise ParameterError(f"{option} {path}: {exc.strerror or exc}") from None


def _check_folder(path: Path, option: str, make: bool) -> Path:
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
    Own the output folder `path` for one run and yield the staging folder to write into. Claiming removes nothing:
    it checks the folder (`check_folder`), takes its LOCK (refused while another live run holds it), reads the
    previous run's MANIFEST (a damaged one is refused) and refuses a folder holding files this tool did not write,
    or wrote and someone changed since, unless `force` (they are then left alone). When the run finishes its files
    replace the previous run's and the manifest is rewritten; on any error or signal the staging folder is removed
    and the previous results stay as they were. Files written through `atomic_path` into `path` itself (not the
    staging folder) are listed too.
    """
    first_made = _first_missing(Path(path))
    path = check_folder(path, option).resolve()
    lock = path / LOCK
    _take_lock(lock, path, option)
    try:
        claim = _open(path, force, option)
        _CLAIMED[path] = claim
        try:
            yield claim.staging
            _commit(claim)
        finally:
            _CLAIMED.pop(path, None)
            _remove_staging(claim.staging)
    except BaseException:
        lock.unlink(missing_ok=True)
        if first_made is not None:  # folders this run made go too, when it leaves them empty
            _remove_empty(path, first_made.resolve())
        raise
    lock.unlink(missing_ok=True)


def _first_missing(path: Path) -> Path | None:
    """The outermost missing folder of `path` (the one `check_folder` makes first), None if `path` exists."""
    missing = None
    with contextlib.suppress(OSError):
        while not path.exists() and path != path.parent:
            missing, path = path, path.parent
    return missing


def _remove_empty(path: Path, top: Path) -> None:
    """Remove `path` and its parents up to `top` while they are empty."""
    if top != path and top not in path.parents:
        return
    for folder in (path, *path.parents):
        with contextlib.suppress(OSError):
            folder.rmdir()  # only when empty
        if folder == top:
            return


def _take_lock(lock: Path, path: Path, option: str) -> None:
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
    return entry.is_dir() and not entry.is_symlink() and (entry / MANIFEST).exists()


def _open(path: Path, force: bool, option: str) -> _Claim:
    """The claim on `path` (its LOCK held): previous manifest read, folder checked, empty staging folder made."""
    _remove_staging(path / STAGING)  # left by a run that was killed: the lock says none is running
    previous = _read_manifest(path, option)
    foreign = _foreign(path, previous)
    changed = sorted(name for name, sha in previous.items() if _exists(path / name) and not _ours(path, name, sha))
    if (foreign or changed) and not force:
        names = foreign + [f"{name} (changed since this tool wrote it)" for name in changed]
        raise ParameterError(
            f"{option} {path}: the folder holds files this tool did not write ({', '.join(names[:3])}"
            f"{', ...' if len(names) > 3 else ''}); give an empty folder, or --force to write beside them"
        )
    staging = path / STAGING
    staging.mkdir()
    return _Claim(path, staging, previous, option)


def _foreign(folder: Path, previous: dict[str, str], sub: str = "") -> list[str]:
    """
    The files and folders under `folder`/`sub` that the previous run did not write (its manifest, lock and staging
    folder, and run folders of their own, are the tool's): a folder the manifest lists files in is looked into.
    """
    listed = {parent.as_posix() for name in previous for parent in PurePosixPath(name).parents}
    names = []
    for entry in sorted((folder / sub).iterdir()):
        name = f"{sub}{entry.name}"
        if (not sub and entry.name in (LOCK, MANIFEST, STAGING)) or name in previous or _is_run(entry):
            continue
        if name in listed and entry.is_dir() and not entry.is_symlink():
            names += _foreign(folder, previous, f"{name}/")
        else:
            names.append(name)
    return names


def _exists(path: Path) -> bool:
    return path.exists() or path.is_symlink()


def _read_manifest(path: Path, option: str) -> dict[str, str]:
    """
    The previous run's files (relative name -> sha256) from its MANIFEST, {} when there is none. ParameterError
    naming the manifest when it is not one this tool wrote: unreadable, not JSON, wrong types, a name outside the
    folder. Nothing is removed on the strength of a damaged manifest.
    """
    manifest = path / MANIFEST
    if not _exists(manifest):
        return {}

    def damaged(problem: str) -> ParameterError:
        return ParameterError(f"{option} {path}: {MANIFEST} {problem}, so nothing was removed; delete it (and the "
                              "files of the run it lists) or pick another folder")

    if manifest.is_symlink() or not manifest.is_file():
        raise damaged("is not a file")
    try:
        doc = json.loads(manifest.read_bytes())
    except (OSError, ValueError) as exc:  # unreadable, not UTF-8, not JSON
        raise damaged(f"cannot be read as JSON ({' '.join(str(exc).split())[:80]})") from None
    if not isinstance(doc, dict) or doc.get("tool") != "sim_origami":
        raise damaged("is not a sim_origami run manifest")
    files, hashes = doc.get("files"), doc.get("sha256")
    if not (isinstance(files, list) and all(isinstance(name, str) for name in files)):
        raise damaged(f"lists its files as {str(files)[:40]!r}, not as a list of names")
    if "version" not in doc and hashes is None:
        raise damaged("was written by an earlier sim_origami without file hashes (a changed file cannot be told "
                      "from its own)")
    if doc.get("version") != MANIFEST_VERSION or not isinstance(hashes, dict) or sorted(files) != sorted(hashes):
        raise damaged(f"is not a version {MANIFEST_VERSION} manifest listing each file with its sha256")
    for name in files:
        if not _relative_name(name):
            raise damaged(f"lists {name!r}, which is not a path inside the folder")
        sha = hashes[name]
        if not (isinstance(sha, str) and len(sha) == 64 and all(c in "0123456789abcdef" for c in sha)):
            raise damaged(f"gives {name!r} a sha256 of {sha!r}")
    return dict(hashes)


def _relative_name(name: str) -> bool:
    """A file name as the manifest writes it: relative, '/'-separated, no '..' or '.' part, no NUL, not the lock,
    manifest or staging folder."""
    if not name or "\x00" in name:
        return False
    parts = PurePosixPath(name).parts
    return (PurePosixPath(name).as_posix() == name and not name.startswith("/")
            and not {"..", "."} & set(parts) and parts[0] not in (LOCK, MANIFEST, STAGING))


def _ours(folder: Path, name: str, sha: str) -> bool:
    """
    The file `name` in `folder` is as this tool wrote it: a regular file reached through no link (so it cannot lie
    outside the folder) whose sha256 is `sha`.
    """
    path = folder / name
    try:
        if os.path.realpath(path) != str(path) or not path.is_file():
            return False
        return _sha256(path) == sha
    except OSError:
        return False


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _commit(claim: _Claim) -> None:
    """
    Swap the finished run in: its staged files replace those of the same name, the previous run's other files are
    removed where unchanged, then the manifest lists the new files. SIGINT and SIGTERM wait until it is done, so an
    interrupted run leaves either the previous results or the new ones, not a mix.
    """
    folder, staging = claim.folder, claim.staging
    staged = sorted(p.relative_to(staging).as_posix() for p in staging.rglob("*") if p.is_file())
    hashes = {name: _sha256(staging / name) for name in staged}
    hashes |= {name: _sha256(folder / name) for name in claim.in_place if (folder / name).is_file()}
    for name in staged:  # checked before anything is replaced, so a clash leaves the previous results whole
        clash = _in_the_way(folder, name)
        if clash is not None:
            raise ParameterError(f"{claim.option} {folder}: {clash} is in the way of this run's {name}, so nothing "
                                 "was replaced; move it and run again")
    blocked = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
    try:
        for name in staged:
            target = folder / name
            target.parent.mkdir(parents=True, exist_ok=True)
            os.replace(staging / name, target)
        emptied = set()
        for name, sha in claim.previous.items():
            if name not in hashes and _ours(folder, name, sha):
                (folder / name).unlink()
                emptied.update(p for p in (folder / name).parents if folder in p.parents)
        for sub in sorted(emptied, key=lambda p: len(p.parts), reverse=True):
            with contextlib.suppress(OSError):
                sub.rmdir()  # only when empty: a file of the user's keeps its folder
        _write_manifest(folder, hashes)
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, blocked)


def _in_the_way(folder: Path, name: str) -> str | None:
    """What keeps a new file `name` from its place in `folder` (a link, a folder where the file goes, a file where
    a folder goes; --force leaves such files of the user's there), as a relative name; None when nothing does."""
    target = folder / name
    for p in (target, *target.parents):
        if p == folder:
            return None
        if p.is_symlink() or (p.is_dir() if p == target else p.exists() and not p.is_dir()):
            return p.relative_to(folder).as_posix()
    return None


def _remove_staging(staging: Path) -> None:
    """Remove a staging folder and what a run left in it (a link of that name is removed, not followed)."""
    if staging.is_symlink() or staging.is_file():
        staging.unlink()
    elif staging.is_dir():
        shutil.rmtree(staging)


def _write_manifest(path: Path, hashes: dict[str, str]) -> None:
    doc = {"tool": "sim_origami", "version": MANIFEST_VERSION, "pid": os.getpid(), "files": sorted(hashes),
           "sha256": dict(sorted(hashes.items()))}
    write_text(path / MANIFEST, json.dumps(doc, indent=1) + "\n")


def _record(path: Path) -> None:
    """List a file written straight into a claimed folder (not its staging folder) in that folder's next manifest."""
    path = path.resolve()
    holders = [claim for claim in _CLAIMED.values() if claim.folder in path.parents]
    if not holders:
        return
    claim = max(holders, key=lambda c: len(c.folder.parts))
    if claim.staging in path.parents or path.name == MANIFEST:
        return  # staged files are found when the run finishes
    name = path.relative_to(claim.folder).as_posix()
    if name not in claim.in_place:
        claim.in_place.append(name)


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
