"""Files written whole or not at all: a temporary file in the same folder, synced, then renamed over the
target (os.replace is atomic on one file system), so a reader never sees half a report and a crash leaves
the old file. The C++ counterpart is biovision_common::writeFileAtomically."""

import os
import tempfile


def _umask():
    """The process's umask, read without changing it (os.umask's set-and-restore would briefly give the
    node's other threads a umask of 0)."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    return 0o022


def write_atomically(path, data):
    """Writes `data` (str: UTF-8 text, bytes: as is) to `path` atomically.

    The file gets the mode a plain open() would give (0666 less the umask; tempfile's own 0600 left the
    demo's reports unreadable to other users). Raises OSError when the folder is missing or not writable;
    the temporary file is removed then.
    """
    folder = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(dir=folder, prefix="." + os.path.basename(path) + ".")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode("utf-8") if isinstance(data, str) else data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
