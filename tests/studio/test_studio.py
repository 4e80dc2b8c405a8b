"""mechfem studio without a browser: the design session (edits on the kept compiled model, refused edits, branch
changes, undo and redo, saving), the view the page draws, and the server's token and loopback-only address.

The four-bar template is checked against a closed form: with the crank A0-A at angle 0, A = (a, 0), and the rocker
B0-B closes the triangle A, B, B0 (sides: coupler b, rocker c, A-B0 d = 4 - a); the rocker angle psi is 180 deg minus
the angle at B0 (law of cosines) on the branch with B above the frame line, and minus that on the other."""

from __future__ import annotations

import json
import math
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("starlette")
pytest.importorskip("uvicorn")
websockets = pytest.importorskip("websockets")
websockets_sync = pytest.importorskip("websockets.sync.client")

import mechfem  # noqa: E402
from mechfem.cli import command as cli  # noqa: E402
from mechfem.run import compiled  # noqa: E402
from mechfem.studio_app import missing  # noqa: E402
from mechfem.studio_app.actions import Actions, examples  # noqa: E402
from mechfem.studio_app.delta import GONE, changes, merged  # noqa: E402
from mechfem.studio_app.scene import scene  # noqa: E402
from mechfem.studio_app.server import dumps, serve_in_thread  # noqa: E402
from mechfem.studio_app.session import EditRefused, Session  # noqa: E402
from mechfem.studio_app.template import four_bar  # noqa: E402
from mechfem.studio_app.view import view  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def psi_closed_form(a: float, b: float = 3.5, c: float = 3.0, up: bool = True) -> float:
    d = 4.0 - a
    at_b0 = math.degrees(math.acos((c * c + d * d - b * b) / (2 * c * d)))
    return 180.0 - at_b0 if up else -(180.0 - at_b0)


def psi(session: Session) -> np.ndarray:
    return np.asarray(session.result.buffers[2])


def test_template_matches_the_closed_form() -> None:
    s = Session(four_bar())
    assert psi(s)[0] == pytest.approx(psi_closed_form(1.0), abs=1e-9)
    assert s.result.positions == 361 and s.result.report.stop_reason() is None


def test_an_edit_changes_a_number_of_the_kept_model_and_reruns_the_motion() -> None:
    s = Session(four_bar())
    model = compiled.kept(s.mechanism).last.model  # type: ignore[union-attr]
    s.edit({"crank.length": 1.2})
    assert psi(s)[0] == pytest.approx(psi_closed_form(1.2), abs=1e-9)
    # The same compiled model ran: the deck was neither written nor read again.
    assert compiled.kept(s.mechanism).last.model is model  # type: ignore[union-attr]
    assert len(compiled.kept(s.mechanism).by_topology) == 1
    assert s.result.positions == 361


def test_an_edit_that_cannot_be_assembled_is_refused_and_the_last_good_design_kept() -> None:
    s = Session(four_bar())
    before = psi(s).copy()
    with pytest.raises(EditRefused, match="rocker|assembl|position 1") as refused:
        s.edit({"rocker.length": 10.0})
    assert "Traceback" not in str(refused.value)
    assert s.mechanism["rocker.length"].value == 3.0
    assert np.array_equal(psi(s), before) and not s.can_undo


def test_an_edit_whose_motion_stops_at_a_limit_is_refused() -> None:
    s = Session(four_bar())
    # 2.6 + 4 > 3.5 + 3: Grashof's condition fails, the crank cannot turn all the way round.
    with pytest.raises(EditRefused, match="stops at position"):
        s.edit({"crank.length": 2.6})
    assert s.mechanism["crank.length"].value == 1.0 and s.result.positions == 361


def test_dragging_a_moving_point_across_chooses_the_other_branch_and_says_so() -> None:
    s = Session(four_bar())
    outcome = s.edit({"B": (3.0, -2.8)})
    assert outcome.branch is not None and "other branch" in outcome.branch
    assert psi(s)[0] == pytest.approx(psi_closed_form(1.0, up=False), abs=1e-9)
    assert s.edit({"B": (3.1, -2.7)}).branch is None


def test_undo_and_redo_restore_values_and_results() -> None:
    s = Session(four_bar())
    s.edit({"crank.length": 1.2})
    s.edit({"B0": (4.2, 0.1)})
    s.undo()
    assert s.mechanism["B0"].x.value == 4.0 and psi(s)[0] == pytest.approx(psi_closed_form(1.2), abs=1e-9)
    s.undo()
    assert s.mechanism["crank.length"].value == 1.0 and not s.can_undo
    s.redo()
    assert s.mechanism["crank.length"].value == 1.2 and s.can_redo
    with pytest.raises(EditRefused, match="nothing to undo"):
        Session(four_bar()).undo()


def test_the_moves_of_one_drag_are_undone_together() -> None:
    s = Session(four_bar())
    for k in range(3):
        s.edit({"B0": (4.0 + 0.1 * (k + 1), 0.0)}, group=7)
    s.edit({"crank.length": 1.1})
    s.undo()
    s.undo()
    assert s.mechanism["B0"].x.value == 4.0 and not s.can_undo


def test_save_writes_deck_data_set_and_report_that_mechfem_run_reproduces(tmp_path: Path) -> None:
    s = Session(four_bar(steps=72))
    s.edit({"crank.length": 1.1, "coupler.v": 0.9})
    files = s.save(tmp_path / "mine.mec")
    assert sorted(p.name for p in files) == ["mine.csv", "mine.html", "mine.mec", "mine.prt"]
    text = (tmp_path / "mine.mec").read_text()
    assert "NAMES" in text and "UNITS ANGLE deg" in text
    out = tmp_path / "cli"
    assert cli.main(["run", str(tmp_path / "mine.mec"), "-o", str(out), "--no-media", "-q"]) == 0
    rows = np.loadtxt(out / "mine.csv", delimiter=",", skiprows=1, ndmin=2)
    assert rows.shape[0] == 73
    # Column 2 of the data set is buffer 2, psi (deg): the CLI's run of the saved deck gives the session's numbers.
    np.testing.assert_allclose(rows[:, 1], psi(s), rtol=1e-7, atol=1e-7)


def test_view_has_the_motion_charts_dimensions_and_points() -> None:
    s = Session(four_bar())
    data = json.loads(dumps(view(s)))
    assert len(data["frames"]) == 361 and len(data["scene"]["frames"]) == 361
    assert [d["name"] for d in data["studio"]["dimensions"]][:2] == ["crank.length", "phi"]
    assert {d["name"]: d["unit"] for d in data["studio"]["dimensions"]}["phi"] == "deg"
    assert [p["name"] for p in data["studio"]["points"]] == ["A0", "B0", "A", "B", "C"]
    assert data["det"]["limits"] == [] and data["stop"] is None
    assert [c["title"] for c in data["cards"]][0] == "coupler curve"
    assert data["paths"][0]["name"] == "C"


@pytest.mark.parametrize(
    "deck", ["fourbar/fourbar.mec", "supply/supply.mec", "slider_crank/slider_crank.mec", "gears/belt_swing_arm.mec"]
)
def test_fast_scene_is_the_reports_scene(deck: str) -> None:
    from mechfem.report.html import _scene
    from mechfem.viz.drawing import MechanismDrawing

    path = ROOT / "examples" / deck
    if not path.exists():
        pytest.skip(f"no {deck}")
    result = mechfem.run_deck(path)
    frames = np.arange(result.positions)
    fast, slow = scene(result, frames), _scene(result, MechanismDrawing(result.model, result.coords), frames)
    assert fast["kinds"] == slow["kinds"] and fast["roles"] == slow["roles"] and fast["moving"] == slow["moving"]
    assert fast["static"] == slow["static"] and fast["bounds"] == slow["bounds"]
    # The report rounds to 6 significant digits, the studio to the 6th digit of the drawing's size.
    x0, x1, y0, y1 = slow["bounds"]
    size = max(x1 - x0, y1 - y0)
    for a, b in zip(fast["frames"], slow["frames"], strict=True):
        for p, q in zip(a, b, strict=True):
            p_, q_ = (np.array(v, dtype=np.float64) for v in (p, q))
            np.testing.assert_allclose(p_, q_, rtol=1e-6, atol=5e-6 * size)


def test_examples_are_offered_and_opened() -> None:
    names = examples()
    assert "fourbar/fourbar.mec" in names
    actions = Actions(None)
    reply = actions.handle({"op": "example", "name": "fourbar/fourbar.mec"}, lambda m: None)
    assert reply["type"] == "design" and reply["design"]["studio"]["name"] == "fourbar"
    bad = actions.handle({"op": "example", "name": "../../etc/passwd"}, lambda m: None)
    assert bad["type"] == "refused" and "not one of the examples" in bad["message"]


def test_a_deck_sent_by_the_browser_that_is_wrong_says_where() -> None:
    reply = Actions(None).handle(
        {"op": "open_text", "name": "bad.mec", "text": "KIN ANA\nTOPOLOGY\nELEM 1 XYZ 1 2\n"}, print
    )
    assert reply["type"] == "refused" and "bad.mec:3:8" in reply["message"] and "ELEM 1 XYZ" in reply["message"]


def test_server_needs_its_token_and_answers_on_loopback_only() -> None:
    running = serve_in_thread(Session(four_bar()))
    try:
        assert running.url.startswith("http://127.0.0.1:")
        page = urllib.request.urlopen(running.url, timeout=10).read().decode()
        assert "mechfem studio" in page and "connect-src ws://127.0.0.1:" in page
        base = running.url.split("?")[0]
        for wrong in (base, base + "?token=wrong"):
            with pytest.raises(urllib.error.HTTPError) as e:
                urllib.request.urlopen(wrong, timeout=10)
            assert e.value.code == 403
        # Another host name (DNS rebinding) is refused too.
        request = urllib.request.Request(running.url, headers={"Host": "evil.example:80"})
        with pytest.raises(urllib.error.HTTPError):
            urllib.request.urlopen(request, timeout=10)
        ws_url = running.url.replace("http://", "ws://").replace("/?token=", "/ws?token=")
        with websockets_sync.connect(ws_url) as ws:
            hello = json.loads(ws.recv())
            assert hello["type"] == "hello" and hello["design"]["positions"] == 361
            ws.send(json.dumps({"op": "edit", "changes": {"crank.length": 1.2}}))
            reply = json.loads(ws.recv())
            # An edit's answer holds what changed of the design the page has.
            assert reply["type"] == "design" and "design" not in reply
            assert reply["changes"]["studio"]["revision"] == 1
        # Without the token the websocket is closed before it opens (the handshake gets 403).
        with pytest.raises(websockets.exceptions.InvalidStatus) as refused:
            websockets_sync.connect(ws_url.split("?")[0] + "?token=nope").close()
        assert refused.value.response.status_code == 403
    finally:
        running.stop()


def test_cli_says_how_to_install_what_is_missing(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from mechfem.studio_app import command

    monkeypatch.setattr(command, "missing", lambda: ["uvicorn"])
    assert cli.main(["studio", "--no-browser"]) == 1
    assert "pip install 'mechfem[studio]'" in capsys.readouterr().err
    assert missing() == []


def test_notebook_widget_edits_a_copy_and_gives_it_back() -> None:
    pytest.importorskip("anywidget")
    original = four_bar(steps=36)
    widget = mechfem.studio(original)
    try:
        assert widget.url.startswith("http://127.0.0.1:") and "token=" in widget.url
        assert "mechfem studio" in urllib.request.urlopen(widget.url, timeout=10).read().decode()
        ws_url = widget.url.replace("http://", "ws://").replace("/?token=", "/ws?token=")
        with websockets_sync.connect(ws_url) as ws:
            ws.recv()
            ws.send(json.dumps({"op": "edit", "changes": {"coupler.v": 0.8}}))
            assert json.loads(ws.recv())["type"] == "design"
        edited = widget.mechanism
        assert isinstance(edited, mechfem.Mechanism) and edited["coupler.v"].value == 0.8
        assert original["coupler.v"].value == 1.2
        assert edited.run().positions == 37
    finally:
        widget.stop()


@pytest.mark.parametrize(
    "name",
    [
        "gears/planetary_gr1.mec",
        "supply/supply_dyn.mec",
        "limits/slider_dead_centre_free.mec",
        "manipulator/manipulator.mec",
    ],
)
def test_examples_of_every_kind_open_and_take_an_edit(name: str) -> None:
    actions = Actions(None)
    opened = actions.handle({"op": "example", "name": name}, lambda m: None)
    assert opened["type"] == "design", opened
    json.loads(dumps(opened))
    pivot = [p for p in opened["design"]["studio"]["points"] if p["fixed"]][-1]
    x, y = pivot["given"]
    edited = actions.handle({"op": "edit", "changes": {pivot["name"]: [x * 1.01 + 0.001, y]}}, lambda m: None)
    assert edited["type"] == "design" and edited["design"]["studio"]["revision"] == 1


def test_six_digits_rounds_a_column_as_the_report_rounds_each_number() -> None:
    from mechfem.report.charts import nums
    from mechfem.studio_app.view import six_digits

    rng = np.random.default_rng(7)
    v = rng.normal(size=5000) * 10.0 ** rng.integers(-12, 12, 5000)
    v = np.concatenate([v, [0.0, -0.0, np.nan, np.inf, -np.inf, 1e-300, 5e-324, 999999.5, 0.1 + 0.2]])
    got, want = six_digits(v).tolist(), nums(v)
    assert [np.isnan(x) for x in got] == [x is None for x in want]
    close = [x == y or abs(x - y) <= 1e-15 * abs(y) for x, y in zip(got, want, strict=True) if y is not None]
    assert all(close)


def test_answers_write_numpy_columns_and_not_finite_numbers_as_null() -> None:
    table = np.array([[1.5, np.nan], [np.inf, 2.0]])
    written = json.loads(dumps({"row": table[0], "column": table[:, 0], "n": np.float64(np.nan)}))
    assert written == {"row": [1.5, None], "column": [1.5, None], "n": None}


def test_the_drawing_kept_from_one_design_draws_the_next_as_a_fresh_one() -> None:
    s = Session(four_bar())
    view(s)
    assert s.drawing_kept["a"].shape[1] == 10
    s.edit({"crank.length": 1.2, "coupler.v": 0.9})
    frames = np.arange(s.result.positions)
    kept, fresh = scene(s.result, frames, s.drawing_kept), scene(s.result, frames)
    assert kept["moving"] == fresh["moving"] and kept["static"] == fresh["static"] and kept["bounds"] == fresh["bounds"]
    np.testing.assert_allclose(_flat(kept["frames"]), _flat(fresh["frames"]), atol=1e-9)
    # A map that no longer draws the design (here: made wrong on purpose) is found anew, not used.
    s.drawing_kept["a"] = s.drawing_kept["a"] + 0.5
    again = scene(s.result, frames, s.drawing_kept)
    np.testing.assert_allclose(_flat(again["frames"]), _flat(fresh["frames"]), atol=1e-9)


def _flat(frames: list[list[np.ndarray]]) -> np.ndarray:
    return np.concatenate([np.asarray(v, dtype=np.float64).ravel() for shapes in frames for v in shapes])


def test_an_edits_changes_put_into_the_design_shown_give_the_new_design() -> None:
    s = Session(four_bar())
    before = view(s)
    s.edit({"crank.length": 1.15})
    after = view(s)
    change = changes(before, after)
    # What the edit does not change is not sent: the drawing's styles and kinds, the columns' names, the cards' titles.
    assert "styles" not in change and "kinds" not in change["scene"] and "frames" not in change
    assert set(change["columns"]["b2"]) == {"values"}
    assert len(dumps(change)) < len(dumps(after))
    assert json.loads(dumps(merged(before, change))) == json.loads(dumps(after))
    # A key the new design has not is said gone; an unchanged design changes nothing but the moving shapes (a list of
    # arrays, sent without looking).
    assert changes({"a": 1, "b": {"c": 2}}, {"b": {}}) == {"b": {GONE: ["c"]}, GONE: ["a"]}
    assert list(changes(after, view(s))) == ["scene"] and list(changes(after, view(s))["scene"]) == ["frames"]


def _psi_extremes(m: mechfem.Mechanism) -> tuple[float, float]:
    """The rocker angle's two extremes, where crank and coupler are folded (A0-B = b - a) and stretched (b + a):
    psi = 180 deg - the angle at B0 of the triangle A0, B0, B."""
    a, b, c = (m[n].value for n in ("crank.length", "coupler.length", "rocker.length"))
    d = float(np.hypot(m["B0"].x.value - m["A0"].x.value, m["B0"].y.value - m["A0"].y.value))
    at_b0 = [math.degrees(math.acos((c * c + d * d - s * s) / (2 * c * d))) for s in (b - a, b + a)]
    return 180.0 - at_b0[1], 180.0 - at_b0[0]


def test_optimise_makes_an_outputs_maximum_reach_a_value_and_shows_its_iterations() -> None:
    actions = Actions(Session(four_bar(steps=72)))
    pushed: list[dict[str, object]] = []
    vary = ["crank.length", "coupler.length", "rocker.length"]
    message = {"op": "optimise", "target": "extremum", "quantity": "psi", "which": "max", "goal": "value"}
    reply = actions.handle({**message, "value": 130.0, "vary": vary}, pushed.append)
    assert reply["type"] == "design", reply
    assert pushed and pushed[0]["type"] == "iteration"
    session = actions.session
    assert session is not None and "The max of psi over the motion is 130 deg" in reply["optimised"]["said"]
    # The motion's positions (5 deg of crank apart) reach 130; the true extremum (closed form) lies a little beyond.
    assert float(np.max(psi(session))) == pytest.approx(130.0, abs=1e-3)
    assert 130.0 - 1e-3 <= _psi_extremes(session.mechanism)[1] < 130.5
    # Pushed up as far as the rocker's length may go (within half and twice its value) and the crank still turns.
    before = _psi_extremes(session.mechanism)[1]
    pushed_up = actions.handle({**message, "goal": "up", "vary": ["rocker.length"]}, pushed.append)
    assert pushed_up["type"] == "design", pushed_up
    assert _psi_extremes(session.mechanism)[1] > before + 1.0 and session.result.report.stop_reason() is None
    # A point's co-ordinate (a length): the coupler point's lowest y over the motion (0.9 in the template) to 1.2.
    fresh = Actions(Session(four_bar(steps=72)))
    low = {"op": "optimise", "target": "extremum", "quantity": "C.y", "which": "min", "goal": "value", "value": 1.2}
    assert fresh.handle({**low, "vary": ["coupler.v"]}, pushed.append)["type"] == "design"
    assert float(np.min(fresh.session.result.value("C.y"))) == pytest.approx(1.2, abs=1e-6)  # type: ignore[union-attr]


def test_optimise_keeps_the_transmission_angle_within_a_bound_with_the_least_change() -> None:
    actions = Actions(Session(four_bar(steps=72)))
    vary = ["crank.length", "coupler.length", "rocker.length"]
    reply = actions.handle({"op": "optimise", "target": "transmission", "transmission": 60, "vary": vary}, print)
    assert reply["type"] == "design", reply
    m = actions.session.mechanism  # type: ignore[union-attr]
    # Closed form: cos mu = (b^2 + c^2 - s^2) / (2 b c), s = |A B0| from d - a (crank towards B0) to d + a.
    a, b, c = (m[n].value for n in vary)
    mu = [math.degrees(math.acos((b * b + c * c - s * s) / (2 * b * c))) for s in (4.0 - a, 4.0 + a)]
    assert 60.0 - 1e-4 <= min(mu) and max(mu) <= 120.0 + 1e-4
    assert min(mu) == pytest.approx(60.0, abs=1e-3)  # the least change: on the bound, not beyond it
    assert "stays within 60 to" in reply["optimised"]["said"]
    refused = actions.handle({"op": "optimise", "target": "transmission", "transmission": 100, "vary": vary}, print)
    assert refused["type"] == "refused" and "between 0 and 90" in refused["message"]


def test_a_kin_opt_deck_saved_from_the_studio_keeps_its_optimise_block_and_runs(tmp_path: Path) -> None:
    actions = Actions(None)
    assert actions.handle({"op": "example", "name": "synthesis/path.mec"}, print)["type"] == "design"
    assert actions.handle({"op": "edit", "changes": {"B0": [2.9, 0.35]}}, print)["type"] == "design"
    saved = actions.handle({"op": "save", "path": str(tmp_path / "mine.mec")}, print)
    assert saved["type"] == "saved", saved
    text = (tmp_path / "mine.mec").read_text()
    block = text[text.index("OPTIMISE") : text.index("STORAGE")]
    assert text.splitlines()[1] == "KIN OPT" and "TARGET 1 path_x.dat" in block and "VARYX 3 1.0 5.0" in block
    # The block's buffers are defined once (there), its target files beside the saved deck.
    assert (
        text.count("BUFX0 9 1") == 1
        and (tmp_path / "path_x.dat").read_bytes() == (ROOT / "examples" / "synthesis" / "path_x.dat").read_bytes()
    )
    assert "XFIX 3 2.9" in text
    # `mechfem run` of the saved deck optimises from the edited design to the deck's known answer: B0 = (3.2, 0),
    # crank 1, rocker 2.5 (the ten points are those of that four-bar).
    assert cli.main(["run", str(tmp_path / "mine.mec"), "-o", str(tmp_path / "out"), "--no-media", "-q"]) == 0
    found = mechfem.Mechanism.from_deck(tmp_path / "out" / "mine_opt.mec")
    assert found["B0"].x.value == pytest.approx(3.2, abs=1e-6) and found["B0"].y.value == pytest.approx(0, abs=1e-6)
    assert found["crank_length"].value == pytest.approx(1.0, abs=1e-6)
    assert found["rocker_length"].value == pytest.approx(2.5, abs=1e-6)


def test_a_deck_of_the_folder_is_opened_by_its_path_with_the_files_beside_it(tmp_path: Path) -> None:
    # The slider-crank's crank follows a MOV_FUNC table (crank.dat) beside the deck.
    (tmp_path / "sub").mkdir()
    for name in ("slider_crank.mec", "crank.dat"):
        (tmp_path / "sub" / name).write_bytes((ROOT / "examples" / "slider_crank" / name).read_bytes())
    (tmp_path / ".hidden").mkdir()
    (tmp_path / ".hidden" / "x.mec").write_text("KIN ANA\n")
    actions = Actions(None, folder=tmp_path)
    hello = actions.hello()
    assert hello["folder"] == str(tmp_path) and hello["files"] == ["sub/slider_crank.mec"]
    opened = actions.handle({"op": "open_path", "name": "sub/slider_crank.mec"}, print)
    assert opened["type"] == "design", opened
    assert opened["design"]["positions"] == mechfem.run_deck(tmp_path / "sub" / "slider_crank.mec").positions
    # Only the folder's decks: nothing above it, nothing that is not a deck.
    (tmp_path.parent / "outside.mec").write_text("KIN ANA\n")
    for name in ("../outside.mec", str(tmp_path.parent / "outside.mec"), "sub/crank.dat", "sub/none.mec"):
        refused = actions.handle({"op": "open_path", "name": name}, print)
        assert refused["type"] == "refused" and "is not a deck of" in refused["message"], name
    # The same deck sent as text by the browser has no folder: it says which file it misses.
    text = (tmp_path / "sub" / "slider_crank.mec").read_text()
    missing_table = actions.handle({"op": "open_text", "name": "slider_crank.mec", "text": text}, print)
    assert missing_table["type"] == "refused" and "crank.dat" in missing_table["message"]
    saved = actions.handle({"op": "save", "path": str(tmp_path / "sub" / "again.mec")}, print)
    assert saved["type"] == "saved" and "sub/again.mec" in saved["decks"]
    assert Actions(None).handle({"op": "open_path", "name": "x.mec"}, print)["type"] == "refused"


def test_the_studio_page_and_the_report_share_one_head() -> None:
    from mechfem.report.html import render_report
    from mechfem.studio_app.page import render_page

    page = render_page("127.0.0.1:8765")
    report = render_report(Session(four_bar(steps=12)).result)
    assert "{{" not in page and "<title>mechfem studio</title>" in page
    assert "img-src data: blob:; connect-src ws://127.0.0.1:8765" in page
    policy = """content="default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:"""
    # The report's policy allows no connection at all; the rest of the head is the same text in both pages.
    assert policy + '">' in report and "connect-src" not in report.split("</head>")[0]
    common = '<meta name="viewport" content="width=device-width, initial-scale=1">\n<title>'
    assert common in page and common in report


def test_a_mechanism_with_a_shape_no_map_draws_keeps_its_map_between_edits() -> None:
    deck = ROOT / "examples" / "gears" / "belt_swing_arm.mec"
    s = Session(mechfem.Mechanism.from_deck(deck), deck)
    view(s)
    a, slow = s.drawing_kept["a"], s.drawing_kept["slow"]
    assert slow.any() and not slow.all()  # the belt's wraps are drawn by the drawing, the rest by the map
    pivot = next(p for p in s.points() if p["fixed"])
    s.edit({pivot["name"]: (pivot["given"][0] + 0.01, pivot["given"][1])})
    frames = np.arange(s.result.positions)
    kept, fresh = scene(s.result, frames, s.drawing_kept), scene(s.result, frames)
    assert s.drawing_kept["a"] is a
    assert kept["static"] == fresh["static"] and kept["bounds"] == fresh["bounds"]
    np.testing.assert_allclose(_flat(kept["frames"]), _flat(fresh["frames"]), atol=1e-9)


def test_cli_refuses_a_folder_that_is_not_there(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["studio", "--folder", str(tmp_path / "none"), "--no-browser"]) == 1
    assert f"--folder {tmp_path / 'none'}: no such folder" in capsys.readouterr().err


def _four_bar_in_mm(steps: int) -> mechfem.Mechanism:
    """The template four-bar with its lengths in mm (every length times 1000)."""
    m = mechfem.Mechanism("fourbar_mm", length="mm", angle="deg")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4000.0, 0.0)
    a, b, c = m.point("A", 1000.0, 0.0), m.point("B", 3200.0, 2800.0), m.point("C", 1900.0, 1500.0)
    m.bar("crank", a0, a, length=1000.0, angle=mechfem.Driven(0.0, name="phi"))
    m.ternary2("coupler", a, b, c, length=3500.0, u=1500.0, v=1200.0)
    m.bar("rocker", b0, b, length=3000.0, angle=mechfem.Output("psi"))
    m.motion = mechfem.Motion.by(steps, 360.0, unit="deg")
    return m


def test_optimise_in_a_model_in_mm_reaches_the_value_given_in_mm() -> None:
    # The coupler point's lowest y (900 mm in the template) asked to reach 1200 mm, as in metres above: the page's
    # value, the dimensions and the result all in the model's mm.
    actions = Actions(Session(_four_bar_in_mm(72)))
    low = {"op": "optimise", "target": "extremum", "quantity": "C.y", "which": "min", "goal": "value", "value": 1200.0}
    reply = actions.handle({**low, "vary": ["coupler.v"]}, lambda _: None)
    assert reply["type"] == "design", reply
    session = actions.session
    assert session is not None
    assert float(np.min(session.result.value("C.y"))) == pytest.approx(1200.0, abs=1e-3)
    assert 1200.0 < session.mechanism["coupler.v"].value < 2400.0
