"""The classroom page: fields and sliders, the block on the moving table, the traces, the verdict.

Built with Panel on Bokeh (``pip install shaketable[classroom]``): Panel serves a page
from this machine with its own JavaScript (no internet), gives text fields, sliders and
buttons whose changes reach Python at once, and runs a periodic callback that moves the
drawing; the figures are plain Bokeh figures whose data sources are updated in place
(the block's corners, the table) or streamed (the traces, revealed as time advances).
Every recomputation is :func:`shaketable.classroom.model.compute`; this module only
draws what it returns.
"""

from __future__ import annotations

import socket
import time
from dataclasses import fields
from pathlib import Path
from typing import Any

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource, Range1d
from bokeh.models.annotations import Label, Span
from bokeh.plotting import figure

from shaketable.classroom.model import (
    COMPARE,
    FIELD_LABELS,
    FRAME_STEP,
    LESSONS,
    MOTIONS,
    PULSE_SHAPES,
    FieldError,
    Picture,
    Settings,
    check,
    compute,
    scene_toml,
)

__all__ = ["ClassroomPage", "free_port", "serve"]

#: Redraws a second while the drawing moves.
FPS = 20

#: Playback speeds offered: simulated seconds per second.
SPEEDS = {"real time": 1.0, "slowed ×2": 0.5, "slowed ×4": 0.25, "fast ×2": 2.0}

#: Colours of the two blocks (faces, traces), as in the animations.
FACES = ("#9ec5e8", "#f6b98a")
LINES = ("#1f77b4", "#ff7f0e")

#: Colours of the mode band (those of the planar figure's band and the mode map).
MODE_COLOURS = {"rest": "#eeeeee", "slide": "#8fbbd9", "rock": "#f2b06b",
                "slide-rock": "#a4d19b", "flight": "#c5a5d9", "overturned": "#d62728"}

#: Slider ranges by the unit a field is typed in: (low, high, step).
SLIDER_RANGES = {"in": (1.0, 240.0, 1.0), "ft": (0.2, 20.0, 0.1), "m": (0.05, 6.0, 0.01),
                 "cm": (5.0, 600.0, 1.0), "mm": (50.0, 6000.0, 10.0), "g": (0.0, 1.5, 0.01),
                 "m/s2": (0.0, 15.0, 0.1), "gal": (0.0, 1500.0, 10.0), "hz": (0.1, 20.0, 0.1),
                 "s": (0.02, 2.0, 0.01), "": (0.0, 1.0, 0.005), "alpha": (0.0, 0.99, 0.01),
                 "deg": (0.0, 30.0, 0.5), "rad": (0.0, 0.5, 0.005)}

#: Fields with a slider beside their text, and the kind of quantity each holds.
SLIDERS = {"height": "length", "width": "length", "cor": "", "static_friction": "",
           "dynamic_friction": "", "frequency": "frequency", "amplitude": "acceleration",
           "vertical": "acceleration", "pulse_amplitude": "acceleration",
           "pulse_length": "time", "record_scale": "", "theta0": "angle", "second": None}


def _split(text: str) -> tuple:
    """(number, unit) of a value as typed: ``"30 in"`` -> (30.0, "in"); None when not one."""
    text = str(text).strip()
    number = text.rstrip("abcdefghijklmnopqrstuvwxyzαABCDEFGHIJKLMNOPQRSTUVWXYZ/²2^ ")
    unit = text[len(number):].strip().lower().replace("^", "")
    try:
        return float(number), unit
    except ValueError:
        return None, unit


class _Field:
    """A text field (a value with its unit), an optional slider beside it and a message."""

    def __init__(self, name: str, value: str, on_change, slider: bool):
        label = FIELD_LABELS[name]
        self.name, self.on_change, self._quiet = name, on_change, False
        self.text = pn.widgets.TextInput(name=label, value=value, width=120,
                                         css_classes=[f"st-{name.replace('_', '-')}"])
        self.message = pn.pane.HTML("", css_classes=[f"st-{name.replace('_', '-')}-message"],
                                    styles={"color": "#b00020", "font-size": "12px"},
                                    margin=(0, 5), width=260)
        self.slider = None
        if slider:
            self.slider = pn.widgets.FloatSlider(name="", start=0.0, end=1.0, step=0.01,
                                                 value=0.5, width=150, margin=(24, 5, 0, 5),
                                                 css_classes=[f"st-{name.replace('_', '-')}"
                                                              "-slider"], show_value=False)
            self.slider.param.watch(self._slid, "value")
            self._fit_slider(value)
        self.text.param.watch(self._typed, "value")
        self.view = pn.Column(pn.Row(self.text, *([self.slider] if self.slider else [])),
                              self.message, margin=0)

    def _fit_slider(self, text: str) -> None:
        if self.slider is None:
            return
        number, unit = _split(text)
        if number is None or (unit not in SLIDER_RANGES and not (
                unit.startswith("m/s") and "m/s2" in SLIDER_RANGES)):
            return
        low, high, step = SLIDER_RANGES.get(unit, SLIDER_RANGES["m/s2"])
        self._quiet = True
        try:
            self.slider.param.update(start=min(low, number), end=max(high, number), step=step,
                                     value=number)
            self.slider.name = ""
        finally:
            self._quiet = False

    def _slid(self, event) -> None:
        if self._quiet:
            return
        _, unit = _split(self.text.value or "")
        value = f"{event.new:.4g}" + (f" {unit}" if unit else "")
        self._quiet = True
        try:
            self.text.value = value
        finally:
            self._quiet = False
        self.on_change()

    def _typed(self, event) -> None:
        if self._quiet:
            return
        self._fit_slider(event.new)
        self.on_change()

    def set(self, value: str) -> None:
        """Show ``value`` without recomputing (a lesson loads many fields at once)."""
        self._quiet = True
        try:
            self.text.value = value
        finally:
            self._quiet = False
        self._fit_slider(value)

    def show(self, message: str) -> None:
        self.message.object = message
        self.message.visible = bool(message)


class ClassroomPage:
    """One visitor's page: its inputs, its figures, its animation.

    Parameters
    ----------
    out : Path
        Folder the save button writes the scene and the figure to.
    settings : Settings, optional
        The first inputs shown (default: the first lesson).
    autoplay : bool
        A lesson starts playing when it is shown (the page's address with ``?play=0``:
        not until the play button is pressed).
    """

    def __init__(self, out: Path, settings: Settings | None = None, autoplay: bool = True):
        self.out = Path(out)
        self.autoplay = autoplay
        self.picture: Picture | None = None
        self.t, self._last = 0.0, 0.0
        self._revealed: list[int] = []
        self._callback: Any = None
        self._loading = False
        first = settings or LESSONS["period"].settings
        self.fields = {item.name: _Field(item.name, str(getattr(first, item.name)),
                                         self.recompute, item.name in SLIDERS)
                       for item in fields(Settings) if item.name in FIELD_LABELS}
        self.choices = {
            "motion": pn.widgets.RadioButtonGroup(name="table motion", options=list(MOTIONS),
                                                  value=first.motion, css_classes=["st-motion"]),
            "pulse_shape": pn.widgets.Select(name="pulse shape", options=list(PULSE_SHAPES),
                                             value=first.pulse_shape, width=120),
            "record": pn.widgets.Select(name="record", value=first.record, width=200,
                                        options=_records()),
            "compare": pn.widgets.Select(name="second block differs by", options=list(COMPARE),
                                         value=first.compare, width=150,
                                         css_classes=["st-compare"]),
        }
        self.switches = {
            "friction": pn.widgets.Checkbox(name="friction (the planar block: it may slide)",
                                            value=first.friction, css_classes=["st-friction"]),
            "record_vertical": pn.widgets.Checkbox(name="with its vertical",
                                                   value=first.record_vertical),
            "pitch": pn.widgets.Checkbox(name="table pitch 12 Hz (Section 3.7)",
                                         value=first.pitch),
        }
        for widget in [*self.choices.values(), *self.switches.values()]:
            widget.param.watch(lambda event: self.recompute(), "value")
        self.lesson = pn.widgets.RadioButtonGroup(
            name="lesson", options=["your block"] + [lesson.title for lesson in LESSONS.values()],
            value=LESSONS["period"].title if settings is None else "your block",
            css_classes=["st-lesson"], button_type="primary")
        self.lesson.param.watch(self._lesson, "value")
        self.look_for = pn.pane.Markdown("", css_classes=["st-look-for"], width=900)
        self.speed = pn.widgets.Select(name="speed", options=list(SPEEDS), value="real time",
                                       width=120)
        self.play = pn.widgets.Button(name="▶ play", button_type="success", width=90,
                                      css_classes=["st-play"])
        self.play.on_click(lambda event: self._locked(self.toggle))
        self.restart = pn.widgets.Button(name="⟲ from the start", width=130)
        self.restart.on_click(lambda event: self._locked(self.start, 0.0))
        self.save_button = pn.widgets.Button(name="save figure and scene", button_type="primary",
                                             width=180, css_classes=["st-save"])
        self.save_button.on_click(lambda event: self._save())
        self.status = pn.pane.HTML("", css_classes=["st-status"], width=900)
        self.numbers = pn.pane.HTML("", css_classes=["st-numbers"], width=900)
        self._figures()
        if settings is None:
            self._show_lesson(LESSONS["period"].title, play=False)
            document = pn.state.curdoc
            if autoplay and document is not None and document.session_context is not None:
                # the first lesson plays once the browser has drawn the page, not while
                # the page is still loading
                pn.state.onload(lambda: self._locked(self.start, 0.0, True))
        else:
            self.recompute()

    # ------------------------------------------------------------------ inputs
    def settings(self) -> Settings:
        """The inputs as the page shows them."""
        values: dict[str, Any] = {name: item.text.value for name, item in self.fields.items()}
        values.update({name: widget.value for name, widget in self.choices.items()})
        values.update({name: widget.value for name, widget in self.switches.items()})
        return Settings(**values)

    def load(self, settings: Settings) -> None:
        """Show ``settings`` in the fields and recompute once."""
        self._loading = True
        try:
            for name, item in self.fields.items():
                item.set(str(getattr(settings, name)))
            for name, widget in {**self.choices, **self.switches}.items():
                widget.value = getattr(settings, name)
        finally:
            self._loading = False
        self.recompute()

    def _lesson(self, event) -> None:
        self._show_lesson(event.new)

    def _show_lesson(self, title: str, play: bool = True) -> None:
        for lesson in LESSONS.values():
            if lesson.title == title:
                self.look_for.object = (f"**{lesson.title}.** {lesson.look_for} "
                                        f"(`shaketable run {lesson.scene}` runs the same "
                                        "blocks.)")
                self.load(lesson.settings)
                self._locked(self.start, 0.0, self.autoplay and play)
                return
        self.look_for.object = ("**Your block.** Change any field or slider: the page "
                                "recomputes at once. Give a second block (a COR, a release "
                                "angle or a height) to compare.")

    def recompute(self) -> bool:
        """Run the page's inputs and redraw; a bad field shows its message, the page stays."""
        if self._loading:
            return False
        settings = self.settings()
        messages = check(settings)
        for name, item in self.fields.items():
            item.show(messages.get(name, ""))
        if messages:
            self.status.object = ("<span style='color:#b00020'>fix the field marked in red; "
                                  "the picture shows the last good inputs</span>")
            return False
        try:
            picture = compute(settings)
        except FieldError as error:
            if error.field in self.fields:
                self.fields[error.field].show(str(error))
            self.status.object = f"<span style='color:#b00020'>{_escape(str(error))}</span>"
            return False
        except ValueError as error:
            self.status.object = f"<span style='color:#b00020'>{_escape(str(error))}</span>"
            return False
        self.status.object = ""
        self._locked(self.draw, picture)
        return True

    def _locked(self, function, *args) -> None:
        """Call ``function(*args)`` holding the document's lock: a widget's callback runs
        without it, and the Bokeh figures (not Panel's own objects) may change only with it.
        Without a served document (tests, the benchmark) the call is direct."""
        document = pn.state.curdoc
        if document is not None and document.session_context is not None:
            document.add_next_tick_callback(lambda: function(*args))
        else:
            function(*args)

    # ------------------------------------------------------------------ figures
    def _figures(self) -> None:
        tools = "pan,wheel_zoom,reset,save"
        self.stage = figure(width=640, height=330, tools=tools, toolbar_location="right",
                            x_range=Range1d(start=-1, end=1), y_range=Range1d(start=-0.1, end=1),
                            title="the block on the shaking table")
        self.stage.xgrid.visible = self.stage.ygrid.visible = False
        self.table_source = ColumnDataSource({"left": [0.0], "right": [1.0], "bottom": [-0.1],
                                              "top": [0.0]})
        self.stage.quad(source=self.table_source, left="left", right="right", bottom="bottom",
                        top="top", fill_color="#8c8c8c", line_color="#333333")
        self.block_sources = [ColumnDataSource({"x": [], "y": []}) for _ in range(2)]
        self.block_glyphs = [self.stage.patch("x", "y", source=source, fill_color=FACES[k],
                                              line_color=LINES[k], line_width=1.5)
                             for k, source in enumerate(self.block_sources)]
        self.clock = Label(x=8, y=240, x_units="screen", y_units="screen", text="t = 0.00 s",
                           text_font_size="13px", text_font="monospace")
        self.stage.add_layout(self.clock)
        self.history = figure(width=640, height=190, tools=tools, x_range=Range1d(start=0, end=1),
                              y_range=Range1d(start=-1.6, end=1.6), title="θ/α (|θ/α| > 1: beyond the "
                                                                "block angle)")
        self.history.yaxis.axis_label = "θ/α [-]"
        for sign in (1, -1):
            self.history.add_layout(Span(location=sign, dimension="width", line_color="#d62728",
                                         line_dash="dashed"))
        self.trace_sources = [ColumnDataSource({"t": [], "r": []}) for _ in range(2)]
        self.trace_glyphs = [self.history.line("t", "r", source=source, color=LINES[k],
                                               line_width=1.5)
                             for k, source in enumerate(self.trace_sources)]
        self.ground = figure(width=640, height=150, tools=tools, x_range=self.history.x_range,
                             y_range=Range1d(start=-1, end=1), title="table acceleration")
        self.ground.yaxis.axis_label = "ü [g]"
        self.ground_title: Any = self.ground.title
        self.ground_source = ColumnDataSource({"t": [], "a": []})
        self.ground.line("t", "a", source=self.ground_source, color="#444444")
        self.band = figure(width=640, height=110, tools="", toolbar_location=None,
                           x_range=self.history.x_range, y_range=Range1d(start=0, end=2),
                           title="what the block does (mode)")
        self.band.yaxis.visible = False
        self.band.xaxis.axis_label = "time [s]"
        self.band_source = ColumnDataSource({"left": [], "right": [], "bottom": [], "top": [],
                                             "colour": [], "mode": []})
        self.band.quad(source=self.band_source, left="left", right="right", bottom="bottom",
                       top="top", fill_color="colour", line_color=None, legend_field="mode")
        self.band.legend.label_text_font_size = "9px"
        self.band.add_layout(self.band.legend[0], "right")
        self.cursors = [Span(location=0, dimension="height", line_color="#1f77b4",
                             line_width=1.5) for _ in range(3)]
        for plot, cursor in zip((self.history, self.ground, self.band), self.cursors):
            plot.add_layout(cursor)

    def draw(self, picture: Picture) -> None:
        """Show a new picture from its first frame (and keep playing if it was)."""
        self.picture = picture
        count = len(picture.runs)
        for k, glyph in enumerate(self.block_glyphs):
            glyph.visible = self.trace_glyphs[k].visible = k < count
        x_low = min(float(outline[:, :, 0].min()) for outline in picture.outlines)
        x_high = max(float(outline[:, :, 0].max()) for outline in picture.outlines)
        tallest = max(run.block.height for run in picture.runs)
        span = max(run.block.height + run.block.width for run in picture.runs)
        x_low, x_high = x_low - 0.3 * span, x_high + 0.3 * span
        y_high = 1.2 * max(tallest, max(float(o[:, :, 1].max()) for o in picture.outlines))
        thickness = 0.06 * tallest
        # equal scales: widen the short side to the frame's aspect (about 570 x 270 pixels)
        width, height = x_high - x_low, y_high + 2 * thickness
        if width / height < 570 / 270:
            middle = (x_low + x_high) / 2
            x_low, x_high = middle - height * 570 / 270 / 2, middle + height * 570 / 270 / 2
        else:
            y_high = width * 270 / 570 - 2 * thickness
        factor = _factor(picture.unit)
        self._factor = factor
        self.stage.x_range.update(start=x_low / factor, end=x_high / factor)
        self.stage.y_range.update(start=-2 * thickness / factor, end=y_high / factor)
        self.stage.xaxis.axis_label = f"x [{picture.unit}]"
        self.stage.yaxis.axis_label = f"y [{picture.unit}]"
        self._table_half = (x_high - x_low) * 0.42
        self._thickness = thickness
        self.history.x_range.update(start=0.0, end=picture.end)
        peak = float(np.max(np.abs(picture.ground[1]), initial=0.0))
        peak = 1.1 * peak if peak > 0 else 1.0
        self.ground.y_range.update(start=-peak, end=peak)
        self.ground_title.text = ("table acceleration" if picture.data["motion"]["kind"] != "free"
                                  else "table acceleration: the table is at rest")
        self.numbers.object = _numbers_html(picture)
        self.start(0.0, play=self._callback is not None)

    def start(self, t: float, play: bool | None = None) -> None:
        """Go to simulated time ``t`` [s], the traces cleared and revealed up to it."""
        self.t, self._last = t, time.perf_counter()
        self._revealed = [0, 0, 0]
        for source in (*self.trace_sources, self.ground_source):
            source.data = {name: [] for name in source.data}
        self.show(t)
        if play:
            self._play()

    def show(self, t: float) -> None:
        """Draw frame ``t`` [s]: the block(s) and the table there, every trace up to ``t``."""
        picture = self.picture
        if picture is None:
            return
        factor = self._factor
        index = min(int(round(t / FRAME_STEP)), picture.frames.size - 1)
        for k, source in enumerate(self.block_sources):
            if k < len(picture.outlines):
                corners = picture.outlines[k][index] / factor
                source.data = {"x": corners[:4, 0], "y": corners[:4, 1]}
        centre = picture.table[index]
        self.table_source.data = {"left": [(centre - self._table_half) / factor],
                                  "right": [(centre + self._table_half) / factor],
                                  "bottom": [-self._thickness / factor], "top": [0.0]}
        self.clock.text = f"t = {t:6.2f} s   table x = {centre / factor:+.2f} {picture.unit}"
        for k, (times, ratio) in enumerate(picture.traces):
            stop = int(np.searchsorted(times, t, side="right"))
            if stop > self._revealed[k]:
                self.trace_sources[k].stream({"t": times[self._revealed[k]:stop],
                                              "r": ratio[self._revealed[k]:stop]})
                self._revealed[k] = stop
        times, acceleration = picture.ground
        stop = int(np.searchsorted(times, t, side="right"))
        if stop > self._revealed[2]:
            self.ground_source.stream({"t": times[self._revealed[2]:stop],
                                       "a": acceleration[self._revealed[2]:stop]})
            self._revealed[2] = stop
        self.band_source.data = _band_columns(picture, t)
        for cursor in self.cursors:
            cursor.location = t

    # ------------------------------------------------------------------ playback
    def _play(self) -> None:
        if self._callback is None:
            self._last = time.perf_counter()
            self._callback = pn.state.add_periodic_callback(self._tick, period=int(1000 / FPS))
        self.play.name = "❚❚ pause"

    def toggle(self) -> None:
        """Play or pause; play from the start after the end."""
        if self._callback is not None:
            self._callback.stop()
            self._callback = None
            self.play.name = "▶ play"
            return
        if self.picture is not None and self.t >= self.picture.end:
            self.start(0.0)
        self._play()

    def _tick(self) -> None:
        if self.picture is None:
            return
        now = time.perf_counter()
        self.t = min(self.t + (now - self._last) * SPEEDS[self.speed.value], self.picture.end)
        self._last = now
        self.show(self.t)
        if self.t >= self.picture.end and self._callback is not None:
            self._callback.stop()
            self._callback = None
            self.play.name = "▶ play"

    # ------------------------------------------------------------------ saving
    def _save(self) -> None:
        self.save()

    def save(self) -> list:
        """Write the scene (TOML) and the figure (PNG) of what is shown; return the paths."""
        from shaketable.core.files import write_text

        if self.picture is None:
            return []
        self.out.mkdir(parents=True, exist_ok=True)
        number = 1
        while (self.out / f"scene-{number:02d}.toml").exists():
            number += 1
        data = dict(self.picture.data, name=f"classroom-{number:02d}")
        scene = self.out / f"scene-{number:02d}.toml"
        image = self.out / f"figure-{number:02d}.png"
        write_text(scene, scene_toml(data))
        _save_figure(self.picture, image, self.t)
        self.status.object = (f"saved <code class='st-saved'>{_escape(str(scene))}</code> and "
                              f"<code>{_escape(str(image))}</code>: <code>shaketable run "
                              f"{_escape(str(scene))}</code> reproduces it")
        return [scene, image]

    def layout(self):
        """The page (a Panel layout)."""
        f = self.fields
        self.groups = {
            "friction": pn.Column(f["static_friction"].view, f["dynamic_friction"].view,
                                  margin=0),
            "harmonic": pn.Column(f["frequency"].view, f["amplitude"].view, f["vertical"].view,
                                  margin=0),
            "pulse": pn.Column(self.choices["pulse_shape"], f["pulse_amplitude"].view,
                               f["pulse_length"].view, margin=0),
            "record": pn.Column(self.choices["record"], f["record_scale"].view,
                                f["target_pga"].view, self.switches["record_vertical"],
                                pn.pane.Markdown("target PGA (e.g. `0.4 g`) replaces the "
                                                 "scale when given; duration empty: the whole "
                                                 "record", margin=(0, 5), width=280), margin=0),
            "second": pn.Column(f["second"].view, margin=0),
        }
        for widget in (self.choices["motion"], self.choices["compare"], self.switches["friction"]):
            widget.param.watch(lambda event: self._visible(), "value")
        self._visible()
        block = pn.Column("### Block", f["height"].view, f["width"].view, f["cor"].view,
                          pn.pane.Markdown("COR: 0 to 1, or `housner`", margin=(0, 5)),
                          f["theta0"].view, self.switches["friction"], self.groups["friction"],
                          "### Second block", self.choices["compare"], self.groups["second"],
                          width=300)
        motion = pn.Column("### Table motion", self.choices["motion"], self.groups["harmonic"],
                           self.groups["pulse"], self.groups["record"], f["duration"].view,
                           self.switches["pitch"], width=300)
        controls = pn.Row(self.play, self.restart, self.speed, self.save_button)
        pictures = pn.Column(pn.pane.Bokeh(self.stage), pn.pane.Bokeh(self.history),
                             pn.pane.Bokeh(self.ground), pn.pane.Bokeh(self.band))
        return pn.Column(
            "# shaketable classroom: a rigid block on a shaking table",
            self.lesson, self.look_for, controls, self.status,
            pn.Row(pn.Column(pictures, self.numbers, width=680), block, motion))

    def _visible(self) -> None:
        """Only the fields of the motion, friction and second block chosen."""
        kind = self.choices["motion"].value
        for name in ("harmonic", "pulse", "record"):
            self.groups[name].visible = kind == name
        self.groups["friction"].visible = bool(self.switches["friction"].value)
        self.groups["second"].visible = self.choices["compare"].value != "none"


def _records() -> list:
    from shaketable.ground import records

    return list(records.available())


def _factor(unit: str) -> float:
    from shaketable.core.constants import LENGTH_UNITS

    return LENGTH_UNITS.get(unit, 1.0)


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _band_columns(picture: Picture, t: float) -> dict:
    """The mode band's rectangles up to ``t`` [s]: one row per block."""
    columns: dict = {"left": [], "right": [], "bottom": [], "top": [], "colour": [], "mode": []}
    count = len(picture.bands)
    for k, spans in enumerate(picture.bands):
        row = count - 1 - k
        for start, stop, mode in spans:
            if start > t:
                break
            columns["left"].append(start)
            columns["right"].append(min(stop, t))
            columns["bottom"].append(row + 0.1)
            columns["top"].append(row + 0.9)
            columns["colour"].append(MODE_COLOURS.get(mode, "#999999"))
            columns["mode"].append(mode)
    return columns


def _numbers_html(picture: Picture) -> str:
    """The verdict and key numbers, one column per block (``data-run``/``data-key``)."""
    head = "".join(f"<th style='color:{LINES[k]}'>{_escape(label or 'the block')}</th>"
                   for k, label in enumerate(picture.labels))
    rows = ["<tr><td>verdict</td>" + "".join(
        f"<td class='st-verdict' data-run='{k}'>{_escape(verdict)}</td>"
        for k, verdict in enumerate(picture.verdicts)) + "</tr>"]
    for key in picture.numbers[0]:
        rows.append(f"<tr><td>{_escape(key)}</td>" + "".join(
            f"<td class='st-number' data-run='{k}' data-key='{_escape(key)}'>"
            f"{_escape(numbers[key])}</td>" for k, numbers in enumerate(picture.numbers))
            + "</tr>")
    return ("<table style='font-size:14px;border-collapse:collapse' cellpadding='4'>"
            f"<tr><th></th>{head}</tr>{''.join(rows)}</table>")


def _save_figure(picture: Picture, path: Path, t: float) -> None:
    """The figure of what is shown: the animation's frame at ``t`` (rocking blocks), or
    the planar block's figure."""
    from shaketable.plots import base as plots

    if hasattr(picture.runs[0], "mode"):
        plots.save(picture.runs[0].plot(), path)
        return
    from shaketable.plots.animation import snapshot

    snapshot(list(picture.runs) if len(picture.runs) > 1 else picture.runs[0],
             min(max(t, picture.frames[0]), picture.end), out=path, span=(0.0, picture.end))


def free_port(address: str = "localhost") -> int:
    """A TCP port free on ``address`` now (the system's choice)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind((address, 0))
        return int(probe.getsockname()[1])


def serve(*, port: int = 0, address: str = "localhost", browser: bool = True,
          out: str | Path = "classroom-out", settings: Settings | None = None,
          ready=None) -> None:
    """Serve the page on ``address:port`` until Ctrl-C (or the server is stopped).

    Parameters
    ----------
    port : int
        TCP port; 0 picks a free one.
    address : str
        Interface to listen on: ``"localhost"`` (default) lets only this machine in.
    browser : bool
        Open the page in the default browser.
    out : str or Path
        Folder the page's save button writes to.
    settings : Settings, optional
        The first inputs (default: the first lesson).
    ready : callable, optional
        Called with the page's address once the server listens (default: print it).
    """
    import logging

    # a closed tab's last frames have nowhere to go: no warning per frame in the terminal
    logging.getLogger("bokeh.server.views.ws").setLevel(logging.ERROR)
    port = free_port(address) if port == 0 else int(port)
    url = f"http://{'localhost' if address in ('localhost', '127.0.0.1') else address}:{port}/"
    local = address in ("localhost", "127.0.0.1")
    # the browser's origin must match: this machine's names, or any for a shared address
    origins = [f"localhost:{port}", f"127.0.0.1:{port}"] if local else ["*"]
    def page():
        arguments = pn.state.session_args or {}
        autoplay = arguments.get("play", [b"1"])[0] not in (b"0", b"no", b"false")
        return ClassroomPage(Path(out), settings, autoplay=autoplay).layout()

    server = pn.serve({"/": page}, port=port,
                      address=address, websocket_origin=origins, show=False, start=False,
                      title="shaketable classroom", verbose=False,
                      # a closed tab's session (and its animation) ends within 2 s
                      check_unused_sessions_milliseconds=1000,
                      unused_session_lifetime_milliseconds=1000)
    server.start()
    if ready is None:
        print(f"shaketable classroom: {url}  (Ctrl-C stops it)", flush=True)
    else:
        ready(url)
    if browser:
        import webbrowser

        server.io_loop.add_callback(lambda: webbrowser.open(url))
    try:
        server.io_loop.start()
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()

