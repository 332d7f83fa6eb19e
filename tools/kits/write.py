"""kits.write - a kit's plan written to a folder: a new kit (write_kit), or an
existing one brought up to date in place, touching only the files that changed
(sync_kit, for check_kit's builds).
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

from .regions import KitError
from .repository import BUILD_DIR_RE, _in_skipped_dir
from .strip import KitPlan

def write_tree(root: Path, plan: KitPlan, target: Path) -> None:
    """Writes the kit into the new folder `target`."""
    for rel in plan.files:
        destination = target / rel
        destination.parent.mkdir(parents=True, exist_ok=True)
        if rel in plan.contents:
            destination.write_text(plan.contents[rel], encoding="utf-8")
            shutil.copymode(root / rel, destination)
        else:
            shutil.copy2(root / rel, destination)


def write_kit(root: Path, plan: KitPlan, target: Path, force: bool = False) -> None:
    """Writes the kit atomically: into a sibling temporary folder, then renamed
    into place, so an interrupted run never leaves half a kit at `target`."""
    target = target.resolve()
    root = root.resolve()
    if target == root or root in target.parents and not _in_skipped_dir(target.relative_to(root).as_posix() + "/x"):
        raise KitError([f"{target}: expected a folder outside the repository (or inside a build folder), "
                        f"found one inside it; choose another target"])
    if target.exists() and not force and any(target.iterdir()):
        raise KitError([f"{target}: expected a new or empty folder, found one with files; "
                        f"pass --force to replace it"])
    target.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=target.name + ".tmp-", dir=target.parent))
    try:
        write_tree(root, plan, staging)
        if target.exists():
            old = Path(tempfile.mkdtemp(prefix=target.name + ".old-", dir=target.parent))
            os.rename(target, old / "kit")
            os.rename(staging, target)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.rename(staging, target)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise


def sync_kit(root: Path, plan: KitPlan, target: Path) -> int:
    """Updates `target` in place to the kit: rewrites only files whose content
    differs and removes files not in the kit, so an existing build folder there
    rebuilds only what changed. Returns the number of files written."""
    target.mkdir(parents=True, exist_ok=True)
    wanted = set(plan.files)
    written = 0
    for rel in plan.files:
        destination = target / rel
        new = plan.contents[rel].encode("utf-8") if rel in plan.contents else (root / rel).read_bytes()
        if destination.is_file() and destination.read_bytes() == new:
            continue
        destination.parent.mkdir(parents=True, exist_ok=True)
        tmp = destination.with_name(destination.name + ".tmp-kit")
        tmp.write_bytes(new)
        shutil.copymode(root / rel, tmp)
        os.replace(tmp, destination)
        written += 1
    for dirpath, dirnames, filenames in os.walk(target):
        rel_dir = Path(dirpath).relative_to(target).as_posix()
        dirnames[:] = [d for d in dirnames if not (rel_dir == "." and BUILD_DIR_RE.match(d))]
        for name in filenames:
            rel = name if rel_dir == "." else f"{rel_dir}/{name}"
            if rel not in wanted:
                os.remove(Path(dirpath, name))
    return written
