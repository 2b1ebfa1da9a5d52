"""The project stands on its own: its texts cite only documents it contains."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# Built from parts so that this file does not cite them itself.
FOREIGN = [name + ".md" for name in ("MO" + "DEL", "PERI" + "ODIC", "STY" + "LE")]
TEXT = {".md", ".cpp", ".hpp", ".py", ".toml", ".txt", ".sh", ".cmake", ".json"}
PARTS = ("README.md", "docs", "src", "include", "apps", "python", "tests", "examples", "bench",
         "scripts", "CMakeLists.txt", "setup.py", "pyproject.toml")


def project_files():
    for part in PARTS:
        path = ROOT / part
        files = [path] if path.is_file() else sorted(path.rglob("*")) if path.is_dir() else []
        for f in files:
            if f.is_file() and (f.suffix in TEXT or f.name == "CMakeLists.txt"):
                yield f


def test_no_citation_of_documents_the_project_does_not_have():
    found = []
    for f in project_files():
        text = f.read_text(encoding="utf-8", errors="replace")
        for name in FOREIGN:
            if name in text:
                found.append(f"{f.relative_to(ROOT)}: {name}")
    assert not found, found


def test_docs_links_and_model_sections_exist():
    """Every docs/*.md a text names exists, and every 'docs/model.md section N' is a section of
    docs/model.md."""
    model = (ROOT / "docs" / "model.md").read_text(encoding="utf-8")
    sections = set(re.findall(r"^#+ (\d+(?:\.\d+)?)\.? ", model, flags=re.M))
    assert {"1", "1.3", "2", "3", "4", "5", "6", "7", "8"} <= sections, sections
    bad = []
    for f in project_files():
        text = f.read_text(encoding="utf-8", errors="replace")
        for doc in re.findall(r"docs/([A-Za-z0-9_-]+\.md)", text):
            if not (ROOT / "docs" / doc).exists():
                bad.append(f"{f.relative_to(ROOT)}: docs/{doc}")
        for number in re.findall(r"docs/model\.md sections? (\d+(?:\.\d+)?)", text):
            if number not in sections:
                bad.append(f"{f.relative_to(ROOT)}: docs/model.md section {number}")
    assert not bad, bad


def test_readme_names_the_sweep_columns_and_fig22_as_they_are():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "**Sweep results CSV** (`sweep --out`): `case[-]`" in readme
    assert "index[-]" not in readme
    assert "local minimum at G = 20" in readme
