# SPDX-FileCopyrightText: 2026 warptrunc developers
# SPDX-License-Identifier: MIT
"""Sweep stores written by earlier versions, read with their meaning: a column spelled before R_t
was ``Rt`` everywhere, β and E_c/E before the one normalisation (E_c/E*), and the previous
layout (one curve file per case), refused with the reason."""

import json

import numpy as np
import pytest

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")

from sweep_helpers import OPTS, OPTS_CLI, case_ids_on_disk, results_only  # noqa: E402

from warptrunc.sweep import SweepGrid, load, load_curves, run_sweep  # noqa: E402
from warptrunc.sweep.curves import part_files, part_rows  # noqa: E402


def test_store_written_with_rt_measured_m_reads_as_Rt_measured_m(tmp_path):
    """A store from before R_t was spelled ``Rt`` everywhere: the old column reads under the new
    name, from cases.parquet and from the rows kept in the parts alike."""
    import pyarrow.parquet as pq

    out = tmp_path / "s"
    grid = SweepGrid([2.3], [0.01], "0")
    full = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)
    table = pq.read_table(out / "cases.parquet")
    names = ["rt_measured_m" if n == "Rt_measured_m" else n for n in table.column_names]
    pq.write_table(table.rename_columns(names), out / "cases.parquet")
    old = load(out)
    assert "rt_measured_m" not in old and (full["Rt_measured_m"] > 0).all()
    np.testing.assert_array_equal(old["Rt_measured_m"], full["Rt_measured_m"])
    resumed = run_sweep(grid, out, progress=False, device="cpu", options=OPTS)  # nothing recomputed
    np.testing.assert_array_equal(resumed["Rt_measured_m"], full["Rt_measured_m"])
    np.testing.assert_array_equal(resumed["seconds"], full["seconds"])


def test_store_written_before_the_one_normalisation_reads_with_its_meaning(tmp_path):
    """A store written when ``beta`` and ``Ec_over_E`` were E_c/E* (no ``beta_contact_modulus``
    and ``Ec_over_Estar``): read, they are E_c/E = (E*/E)·E_c/E* (E the Young's modulus), the
    old values under the contact-modulus names; from cases.parquet and from the parts alike,
    and a resumed run recomputes nothing."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from warptrunc.material import Material

    out = tmp_path / "s"
    grid = SweepGrid([2.3, 2.6], [0.01], "0")
    new = run_sweep(grid, out, progress=False, device="cpu", options=OPTS.replace(E=200e9, nu=0.3))
    curves_new = load_curves(out)
    ratio = Material(E=200e9, nu=0.3).contact_modulus / 200e9  # 1/(1 − ν²), rigid flat
    assert ratio == pytest.approx(1 / (1 - 0.3**2), rel=1e-15)
    ok = new["beta"].notna()
    np.testing.assert_allclose(new["beta"][ok], new["beta_contact_modulus"][ok] * ratio, rtol=1e-12)
    np.testing.assert_allclose(
        curves_new["Ec_over_E"], curves_new["Ec_over_Estar"] * ratio, rtol=1e-14
    )
    # forge the old layout: E_c/E* under the plain names, the explicit columns absent
    for f in part_files(out / "curves"):
        table = pq.read_table(f)
        rows = [
            [
                {
                    k: (r["beta_contact_modulus"] if k == "beta" else v)
                    for k, v in r.items()
                    if k != "beta_contact_modulus"
                }
                for r in rs
            ]
            for rs in part_rows(f)
        ]
        old = table.drop_columns(["Ec_over_E", "Ec_over_Estar"]).append_column(
            "Ec_over_E", table.column("Ec_over_Estar")
        )
        meta = {**(table.schema.metadata or {}), b"warptrunc.rows": json.dumps(rows).encode()}
        pq.write_table(old.replace_schema_metadata(meta), f)
    cases = pq.read_table(out / "cases.parquet")
    old_cases = cases.drop_columns(["beta", "beta_contact_modulus"])
    old_cases = old_cases.add_column(
        cases.column_names.index("beta"), "beta", cases.column("beta_contact_modulus")
    )
    pq.write_table(old_cases.replace_schema_metadata(cases.schema.metadata), out / "cases.parquet")
    assert "beta_contact_modulus" not in pq.read_schema(out / "cases.parquet").names
    assert isinstance(old_cases, pa.Table)
    cols = ["case_id", "min_pixels", "alpha", "beta", "beta_contact_modulus"]
    pd.testing.assert_frame_equal(load(out)[cols], new[cols], rtol=1e-14)
    back = load_curves(out).sort_values(["case_id", "depth_m"]).reset_index(drop=True)
    ref = curves_new.sort_values(["case_id", "depth_m"]).reset_index(drop=True)
    pd.testing.assert_frame_equal(back[ref.columns], ref, rtol=1e-14)
    (out / "cases.parquet").unlink()  # rebuilt from the parts' rows
    pd.testing.assert_frame_equal(load(out)[cols], new[cols], rtol=1e-14)
    resumed = run_sweep(
        grid, out, progress=False, device="cpu", options=OPTS.replace(E=200e9, nu=0.3)
    )
    np.testing.assert_array_equal(resumed["seconds"], new["seconds"])  # nothing recomputed
    pd.testing.assert_frame_equal(resumed[cols], new[cols], rtol=1e-14)


def _old_layout(out):
    """Turn a store into the previous layout: sweep.json of format 1, one curve file per case
    (its rows in the metadata), cases.parquet without the last case (killed before its flush)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from warptrunc.sweep.read import rows_frame

    rows = {rs[0]["case_id"]: rs for f in part_files(out / "curves") for rs in part_rows(f)}
    curves = load_curves(out)
    for f in part_files(out / "curves"):
        f.unlink()
    for cid, rs in rows.items():
        c = curves[curves.case_id == cid].drop(columns="case_id")
        t = pa.Table.from_pandas(c, preserve_index=False)
        t = t.replace_schema_metadata({b"warptrunc.rows": json.dumps(rs).encode()})
        pq.write_table(t, out / "curves" / f"{cid}.parquet")
    last = max(rows, key=lambda c: rows[c][0]["case_index"])
    df = rows_frame([r for c, rs in rows.items() if c != last for r in rs])
    df.to_parquet(out / "cases.parquet", index=False)
    spec = json.loads((out / "sweep.json").read_text())
    (out / "sweep.json").write_text(json.dumps({**spec, "format": "warptrunc-sweep/1"}))


def test_earlier_layout_refused_with_the_reason(tmp_path):
    """A store of the layout before parts (format 1, written only by development versions
    before 0.1) is refused by load, load_curves, run_sweep and the CLI, naming the way out;
    --overwrite replaces it, with the same case ids."""
    from warptrunc.cli import main

    grid = SweepGrid([2.3, 2.6], [0.01], "0-1")
    out = tmp_path / "s"
    full = run_sweep(grid, out, options=OPTS, progress=False, device="cpu")
    _old_layout(out)
    why = r"s is a sweep store of the layout before warptrunc-sweep/2 .* new --out \(or with --overwrite\)"
    for read in (load, load_curves):
        with pytest.raises(ValueError, match=why):
            read(out)
    with pytest.raises(ValueError, match=why):
        run_sweep(grid, out, options=OPTS, progress=False, device="cpu")
    assert (
        json.loads((out / "sweep.json").read_text())["format"] == "warptrunc-sweep/1"
    )  # untouched
    assert (
        main(
            [
                "sweep",
                "--D",
                "2.3",
                "2.6",
                "--delta",
                "0.01",
                "--seeds",
                "0-1",
                "--n",
                "64",
                *OPTS_CLI,
                "--overwrite",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    again = load(out)
    assert json.loads((out / "sweep.json").read_text())["format"] == "warptrunc-sweep/2"
    pd.testing.assert_frame_equal(results_only(again), results_only(full))
    assert sorted(case_ids_on_disk(out)) == sorted(full.case_id.unique())
    assert all(p.name.startswith("part-") for p in (out / "curves").iterdir())
