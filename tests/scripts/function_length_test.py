#!/usr/bin/env python3
"""scripts/check_function_length.py finds a long function, spares a short one and a marked
data table, and passes on the repository itself.

    tests/scripts/function_length_test.py REPO_ROOT
"""
import pathlib
import subprocess
import sys
import tempfile


def run(script, root, limit):
    return subprocess.run([sys.executable, str(script), str(root), "--max", str(limit)],
                          capture_output=True, text=True)


def main():
    repo = pathlib.Path(sys.argv[1])
    script = repo / "scripts" / "check_function_length.py"
    with tempfile.TemporaryDirectory() as tmp:
        slam = pathlib.Path(tmp) / "slam"
        slam.mkdir()
        body = "".join(f"  x += {i};\n" for i in range(8))
        (slam / "a.cpp").write_text(
            "namespace lifelong {\n"
            "int Long(int x,\n         int y) {\n" + body + "  return x;\n}\n"
            "int Short(int x) { return x; }\n"
            "// Every row (data table).\nint Table() {\n" + body + "  return 0;\n}\n"
            "}  // namespace lifelong\n")
        found = run(script, tmp, 5)
        assert found.returncode == 1, found.stdout
        assert "slam/a.cpp:2: 9 lines: int Long(int x," in found.stdout, found.stdout
        assert "Table" not in found.stdout and "Short" not in found.stdout, found.stdout
        assert run(script, tmp, 9).returncode == 0
    on_repo = run(script, repo, 60)
    assert on_repo.returncode == 0, on_repo.stdout
    print("function_length_test: ok")


if __name__ == "__main__":
    main()
