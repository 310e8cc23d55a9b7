"""The folder of the unrolled kernels (``solvers/_unrolled.py``): Python imports the modules written there and numba
unpickles its cache index next to them, so a folder others can write is not used (the generic kernels run)."""
import os
import stat

import pytest

from hyperrotor import _jit
from hyperrotor.classical.solvers import _unrolled

posix = pytest.mark.skipif(not hasattr(os, "geteuid"), reason="no owners or group/other write bits on Windows")


@pytest.fixture
def cache_root(tmp_path, monkeypatch):
    """``HYPERROTOR_CACHE_DIR`` in a fresh folder, umask 002 (group-writable by default, as on many desktops),
    no folder refused yet and no module cached."""
    root = tmp_path / "root" / "hyperrotor"
    monkeypatch.setenv("HYPERROTOR_CACHE_DIR", str(root))
    monkeypatch.setattr(_unrolled, "_refused", set())
    _unrolled._module.cache_clear()
    old = os.umask(0o002)
    try:
        yield root
    finally:
        os.umask(old)
        _unrolled._module.cache_clear()


def _mode(path):
    return stat.S_IMODE(os.lstat(path).st_mode)


@posix
def test_a_new_folder_and_its_missing_parents_are_private(cache_root):
    folder = _unrolled._folder()
    assert folder == cache_root / "unrolled"
    for path in (cache_root.parent, cache_root, folder):
        assert _mode(path) == 0o700, (path, oct(_mode(path)))
    assert _unrolled._folder() == folder  # (and the private folder is accepted on the next call)


@posix
@pytest.mark.parametrize("mode", [0o775, 0o757, 0o777, 0o1777], ids=["group", "other", "both", "sticky"])
def test_a_folder_others_can_write_is_refused_with_one_warning(cache_root, mode):
    folder = cache_root / "unrolled"
    folder.mkdir(parents=True)
    folder.chmod(mode)
    with pytest.warns(UserWarning, match=r"its group or other users can write it \(mode " + oct(mode)) as record:
        refused = _unrolled._folder()
    assert refused is None and len(record) == 1 and str(folder) in str(record[0].message)
    assert _unrolled._folder() is None  # (one warning per folder and process: a second would be an error here)
    assert record[0].filename == __file__  # (pointed at the caller, not at the package)
    assert _mode(folder) == mode and list(folder.iterdir()) == []  # neither tightened nor written into
    if _jit.JIT_ENABLED and _jit.CACHE_ENABLED:
        assert _unrolled.kernel(3, False) is None  # the generic kernels run


@posix
def test_a_folder_owned_by_someone_else_is_refused(cache_root, monkeypatch):
    folder = cache_root / "unrolled"
    folder.mkdir(parents=True, mode=0o700)
    owner = os.lstat(folder).st_uid
    monkeypatch.setattr(os, "geteuid", lambda: owner + 1)  # (as if another account had made it)
    with pytest.warns(UserWarning, match=rf"owned by user id {owner}, not by this user \({owner + 1}\)"):
        assert _unrolled._folder() is None


@pytest.mark.parametrize("dangling", [False, True], ids=["to-a-folder", "dangling"])
def test_a_symlinked_folder_is_refused(cache_root, tmp_path, dangling):
    target = tmp_path / "elsewhere"
    if not dangling:
        target.mkdir(mode=0o700)  # (private and ours: only the link is wrong)
    cache_root.mkdir(parents=True)
    (cache_root / "unrolled").symlink_to(target, target_is_directory=True)
    with pytest.warns(UserWarning, match="it is a symbolic link"):
        assert _unrolled._folder() is None
    # (left as it is; a dangling link is not followed to create its target)
    assert (cache_root / "unrolled").is_symlink() and target.exists() == (not dangling)


def test_a_private_folder_of_ours_is_used_and_holds_the_kernel(cache_root):
    folder = cache_root / "unrolled"
    folder.mkdir(parents=True)
    folder.chmod(0o755)  # (the old default: not writable by others, accepted as it is)
    assert _unrolled._folder() == folder and _mode(folder) == 0o755
    if _jit.JIT_ENABLED and _jit.CACHE_ENABLED:
        assert _unrolled.kernel(3, False) is not None
        written = list(folder.glob("hyperrotor_unrolled_so3_*.py"))
        assert len(written) == 1 and written[0].read_text() == _unrolled.source(3)


def test_a_file_in_the_way_gives_no_folder_and_no_warning(cache_root):
    cache_root.mkdir(parents=True)
    (cache_root / "unrolled").write_text("")
    assert _unrolled._folder() is None  # (warnings are errors in the tests: none was issued)
