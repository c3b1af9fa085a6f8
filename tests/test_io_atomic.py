"""Temporary files of atomic writes (livemod.dlfl.io.atomic): a killed save's is
removed by a later save, a live writer's is not."""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from livemod.dlfl.io import read_obj, write_obj
from livemod.dlfl.io.atomic import remove_abandoned, temporary_path, write_atomically
from tests.meshes import cube as unit_cube

# a save that writes half of its bytes, says so and waits (for its stdin to close)
HALF_A_SAVE = """
import sys
from livemod.dlfl.io.atomic import atomic_write
with atomic_write(sys.argv[1]) as handle:
    handle.write(b"half of a new mesh")
    handle.flush()
    print("writing", flush=True)
    sys.stdin.read()
"""


def _half_a_save(target: Path) -> subprocess.Popen:
    """A process in the middle of saving ``target`` (its temporary file written)."""
    proc = subprocess.Popen([sys.executable, "-c", HALF_A_SAVE, str(target)],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stdout.readline() == "writing\n"
    return proc


def _temporary_files(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def test_a_killed_saves_temporary_file_is_removed_by_the_next_save(tmp_path):
    target = tmp_path / "mesh.obj"
    target.write_bytes(b"old")
    proc = _half_a_save(target)
    proc.kill()
    proc.communicate(timeout=30)
    [left] = _temporary_files(tmp_path)
    assert left.startswith(".mesh.obj.") and f"-{proc.pid}-" in left
    assert target.read_bytes() == b"old"
    write_atomically(tmp_path / "other.obj", b"new")  # any save into the folder
    assert _temporary_files(tmp_path) == []
    assert target.read_bytes() == b"old"


def test_a_live_writers_temporary_file_is_kept(tmp_path):
    target = tmp_path / "mesh.obj"
    proc = _half_a_save(target)
    try:
        write_atomically(tmp_path / "other.obj", b"new")
        [kept] = _temporary_files(tmp_path)
        assert f"-{proc.pid}-" in kept
    finally:
        proc.communicate(timeout=30)  # closes its stdin: the save finishes
    assert proc.returncode == 0
    assert target.read_bytes() == b"half of a new mesh"
    assert _temporary_files(tmp_path) == []


def test_only_temporary_files_of_gone_writers_on_this_host_are_removed(tmp_path):
    mine = Path(temporary_path(str(tmp_path / "a.obj"))).name
    host, pid, start, rand = mine[len(".a.obj."):-len(".tmp")].split("-")
    gone_pid = _an_unused_pid()
    names = {
        "gone": f".a.obj.{host}-{gone_pid}-{start}-{rand}.tmp",
        # the parent's id, but another start: the id was reused, its writer is gone
        "reused": f".b.obj.{host}-{os.getppid()}-1-{rand}.tmp",
        "live": f".c.obj.{host}-{os.getppid()}-{_start_of(os.getppid())}-{rand}.tmp",
        "mine": mine,
        "other host": f".d.obj.{'0' * 8 if host != '0' * 8 else '1' * 8}-{gone_pid}-5-{rand}.tmp",
        "old form": ".e.obj.0123abcd.tmp",
    }
    for name in names.values():
        (tmp_path / name).write_bytes(b"x")
    removed = remove_abandoned(str(tmp_path))
    assert sorted(removed) == sorted([names["gone"], names["reused"]])
    assert _temporary_files(tmp_path) == sorted(
        names[k] for k in ("live", "mine", "other host", "old form"))


def test_a_staging_folder_of_a_gone_writer_is_removed_with_its_files(tmp_path):
    """A batch killed (SIGKILL) before it removed a variant's staging folder
    (livemod.runner.batch stages a file and its companions in one)."""
    mine = Path(temporary_path(str(tmp_path / "v.obj")))
    host, _, start, rand = mine.name[len(".v.obj."):-len(".tmp")].split("-")
    gone = tmp_path / f".v.obj.{host}-{_an_unused_pid()}-{start}-{rand}.tmp"
    for folder in (mine, gone):
        folder.mkdir()
        (folder / "v.obj").write_bytes(b"mtllib v.mtl\n")
        (folder / "v.mtl").write_bytes(b"newmtl default\n")
    assert remove_abandoned(str(tmp_path)) == [gone.name]
    assert _temporary_files(tmp_path) == [mine.name]  # its writer lives: kept
    assert sorted(os.listdir(mine)) == ["v.mtl", "v.obj"]
    # a staging folder is its writer's alone: a save into it sweeps nothing
    assert remove_abandoned(str(mine)) == []


def test_a_sigterm_killed_save_is_removed_too(tmp_path):
    target = tmp_path / "mesh.obj"
    proc = _half_a_save(target)
    proc.send_signal(signal.SIGTERM)  # no handler: the writer dies as SIGKILL would leave it
    proc.communicate(timeout=30)
    assert len(_temporary_files(tmp_path)) == 1
    write_atomically(target, b"good")
    assert _temporary_files(tmp_path) == [] and target.read_bytes() == b"good"


def _start_of(pid: int) -> int:
    from livemod.dlfl.io.atomic import _start_token

    start = _start_token(pid)
    assert start is not None
    return start


def _an_unused_pid() -> int:
    """The id of a child that has exited and been reaped (free, unless reused since:
    then the start token tells it apart)."""
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait(timeout=30)
    return proc.pid


@pytest.fixture(autouse=True)
def _fresh_sweeps(monkeypatch):
    """Each test's folder is swept at its first save, whatever ran before."""
    monkeypatch.setattr("livemod.dlfl.io.atomic._swept", {})


def test_a_staged_file_moved_into_place_keeps_the_old_mode_and_the_link(tmp_path):
    from livemod.dlfl.io.atomic import move_into_place

    real = tmp_path / "real.obj"
    real.write_bytes(b"old")
    real.chmod(0o600)
    link = tmp_path / "link.obj"
    link.symlink_to(real)
    staged = Path(temporary_path(str(real)))
    staged.write_bytes(b"new")
    move_into_place(str(staged), link)
    assert link.is_symlink() and real.read_bytes() == b"new"
    assert real.stat().st_mode & 0o777 == 0o600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.obj", "real.obj"]
    with pytest.raises(OSError, match=f"cannot write {tmp_path}"):
        move_into_place(str(tmp_path / "gone.tmp"), tmp_path / "x.obj")


# -- the mode of a written file: the umask for a new one, the old one's kept


def test_new_file_mode_follows_the_umask(tmp_path) -> None:
    old = os.umask(0o077)
    try:
        write_obj(unit_cube(), tmp_path / "private.obj")
    finally:
        os.umask(old)
    assert stat.S_IMODE(os.stat(tmp_path / "private.obj").st_mode) == 0o600


def test_replacing_a_read_only_file_keeps_its_mode(tmp_path) -> None:
    path = tmp_path / "ro.obj"
    path.write_bytes(b"old")
    path.chmod(0o444)
    write_obj(unit_cube(), path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o444
    assert read_obj(path).num_faces == 6
    assert os.listdir(tmp_path) == ["ro.obj"]


def test_a_file_in_an_unsynced_folder_is_replaced_without_a_sync(tmp_path, monkeypatch):
    """A worker's scratch outputs skip the syncs; a save anywhere else keeps both
    (the file's and its folder's)."""
    from livemod.dlfl.io import atomic

    monkeypatch.setattr(atomic, "_unsynced", set())
    synced: list[int] = []
    monkeypatch.setattr(os, "fsync", synced.append)
    scratch, kept = tmp_path / "scratch", tmp_path / "kept"
    scratch.mkdir()
    kept.mkdir()
    atomic.write_unsynced(os.path.realpath(scratch))
    for folder in (scratch, kept):
        (folder / "v.obj").write_bytes(b"old")
        write_atomically(folder / "v.obj", b"new")
        assert (folder / "v.obj").read_bytes() == b"new"
        assert _temporary_files(folder) == []
        assert len(synced) == (0 if folder == scratch else 2)
    write_atomically(scratch / "sub.obj", b"x", sync_folder=False)
    assert len(synced) == 2
