"""Bad input is named as the user gave it (the option, the file, the row), and a command that
fails leaves no folder of its own behind."""

from __future__ import annotations

import sys

import pytest

from sawdrift.cli import main


@pytest.fixture
def files(tmp_path):
    (tmp_path / "malformed.toml").write_text('model = "mmd"\n[particle\n')
    (tmp_path / "adir").mkdir()
    (tmp_path / "device3.toml").write_text("device = 3\n")
    (tmp_path / "nanrow.csv").write_text("a,N\n0,0\n0.5,0.35\nnan,0.7\n1,1\n2,2.8\n")
    (tmp_path / "nanrow.toml").write_text('[particle.profile]\nshape = "table"\n'
                                          'file = "nanrow.csv"\n')
    import pandas as pd

    pd.DataFrame([{"model": "mmd", "amplitude": a, "m_star": m, "regime": "stick",
                   "settled": True, "mu": 0.1, "nu": 0.3, "drift_ratio": 0.0}
                  for a in (0.1, 1.0) for m in (0.1, 1.0)]).to_parquet(tmp_path / "sweep.parquet")
    return tmp_path


@pytest.mark.parametrize("line, named", [
    ("field --backward 1 --direct --wavelength 1000 --start nan", "--start = nan"),
    ("field --backward 1 --points 4 --position 0.2", "--position 0.2"),
    ("field --backward 1 --points 4 --set drive.position=0.2", "--set drive.position=0.2"),
    ("run --periods 5 --no-settle --wavelength 1e-300", "drive.wavelength = 1e-300"),
    ("sweep --m-star 0.1 --amplitude 0.3 -o {d}/afile", "-o '{d}/afile'"),
    ("sweep --m-star 0.1 --amplitude 0.3 -o {d}/t.pq", "-o '{d}/t.pq'"),
    ("phase-diagram {d}/sweep.parquet --model mmd --x nosuch -o {d}/x.png", "--x = 'nosuch'"),
    ("run {d}/device3.toml", "device = 3: the device is a table"),
    ("sort {d}/malformed.toml", "is malformed TOML"),
    ("sort {d}/adir", "is a directory, not a TOML file"),
    ("run {d}/nanrow.toml", "every row must be finite: one has a = nan, N = 0.7"),
])
def test_the_line_names_the_option_given(line, named, files, monkeypatch, capsys):
    """--start nan was reported as "drive.position = nan", the field's own setting; -o afile
    as "table = 'afile'" (the API's name; -o t.pq passed the command and failed there); --x
    nosuch as a table that is not a sweep table; device = 3 as "scene: Input should be a valid
    dictionary"; sort said "not valid UTF-8 TOML" for a syntax error and "cannot use 'adir': Is
    a directory"; a profile table of 5 rows, one NaN, was said to need 4 finite rows."""
    monkeypatch.setattr(sys, "argv", ["sawdrift", *line.format(d=files).split()])
    with pytest.raises(SystemExit):
        main()
    assert named.format(d=files) in capsys.readouterr().err


def test_a_run_that_fails_takes_away_the_folder_it_made(tmp_path, monkeypatch, capsys):
    """`run --model mmd,other -o DIR` whose second model fails: exit 2, and the folder the
    command made is not left behind empty."""
    import sawdrift as sd
    import sawdrift.cli.run as cli_run

    real = cli_run._run_one

    def second_fails(scene, *args, **kwargs):
        if scene.model == "jaeger":
            raise sd.SceneError("model 'jaeger': its force is NaN at a* = 1.3")
        return real(scene, *args, **kwargs)

    monkeypatch.setattr(cli_run, "_run_one", second_fails)
    out = tmp_path / "made" / "deeper" / "out"
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", "--model", "mmd,jaeger", "--periods",
                                      "5", "--no-settle", "-o", str(out)])
    with pytest.raises(SystemExit) as exc:
        main()
    assert exc.value.code == 2 and "jaeger" in capsys.readouterr().err
    assert not (tmp_path / "made").exists()  # nor the parents it made (they were left)
    kept = tmp_path / "kept"
    kept.mkdir()
    monkeypatch.setattr(sys, "argv", ["sawdrift", "run", "--model", "mmd,jaeger", "--periods",
                                      "5", "--no-settle", "-o", str(kept)])
    with pytest.raises(SystemExit):
        main()
    assert kept.is_dir()  # a folder that was there before stays
