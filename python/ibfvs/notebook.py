"""The live notebook widget: the web page's runtime in Jupyter, as an
anywidget, with its settings kept equal both ways (docs/python.md).

    import ibfvs
    w = ibfvs.widget("data/meshes/bunny.off", field="rotate:0,1,0")
    w                  # the animated texture, with the page's panel
    w.alpha = 0.2      # the page's alpha slider moves, and the texture follows
    w.step             # what a person set with the step slider
    w.look             # the style chosen in the page's style menu

The scene goes to the page as the page's two parts (its JSON header and its
binary block). The settings a page changes as it runs are traits: alpha,
beta, step (pixels a frame), speed (where the look has no step), scale (the
noise cells' pixels), look (the page's style menu: one of the styles that
take the scene's data; ipywidgets keeps the name `style` for a widget's own
style), playing, loop and hold. `set` takes any scene key: these go to the
running page (style to look); any other prepares the scene again, and the
page starts again on it.
"""

from __future__ import annotations

import json

try:
    import anywidget
    import traitlets
except ImportError as e:  # pragma: no cover - the message is the point
    raise ImportError("ibfvs.widget needs anywidget: pip install 'ibfvs[notebook]' "
                      "(or pip install anywidget)") from e

from . import _ibfvs

# The settings the page changes as it runs (web/src/page.ts's PageControls).
_NUMBERS = ("alpha", "beta", "step", "speed", "scale")
_SWITCHES = ("playing", "loop", "hold")
LIVE = _NUMBERS + ("look",) + _SWITCHES
# Those that are scene keys too (look is the key style), style first: it
# brings the others' defaults.
_KEYS = ("look", "alpha", "beta", "step", "scale", "loop")


class SettingError(traitlets.TraitError, ValueError):
    """A setting the page cannot take (a ValueError, and traitlets' own error)."""


def _uniform(look, name):
    for u in look["uniforms"]:
        if u["name"] == name:
            return u["values"][0]
    return None


class FlowWidget(anywidget.AnyWidget):
    """The animated texture in a notebook, as the web page runs it.

    Made by `ibfvs.widget(...)` or `Animation.widget()`; `animation` is the
    Animation it shows."""

    _esm = _ibfvs.Animation._widget_module() or ""
    _css = _ibfvs.Animation._page_style()

    scene = traitlets.Unicode("").tag(sync=True)
    data = traitlets.Bytes(b"").tag(sync=True)
    alpha = traitlets.Float(None, allow_none=True).tag(sync=True)
    beta = traitlets.Float(None, allow_none=True).tag(sync=True)
    step = traitlets.Float(None, allow_none=True).tag(sync=True)
    speed = traitlets.Float(None, allow_none=True).tag(sync=True)
    scale = traitlets.Float(None, allow_none=True).tag(sync=True)
    look = traitlets.Unicode(None, allow_none=True).tag(sync=True)
    playing = traitlets.Bool(True).tag(sync=True)
    loop = traitlets.Bool(None, allow_none=True).tag(sync=True)
    hold = traitlets.Bool(None, allow_none=True).tag(sync=True)

    def __init__(self, animation, **kwargs):
        if not _ibfvs.Animation._has_page():
            raise RuntimeError("this ibfvs was built without the browser runtime (it needs node "
                               "and npm at build time): no widget")
        self._header = {}
        super().__init__(**kwargs)
        self.animation = animation
        self._send_scene()

    # ---- the scene
    def _send_scene(self):
        """The Animation's scene as the page's parts, with the settings it
        starts from (its first look's), in one message."""
        header, data = self.animation._page_parts()
        self._header = json.loads(header)
        look = self._header["looks"][0]
        image_step = _uniform(look, "u_image_step")
        with self.hold_sync():
            self.data = data
            self.scene = header
            self.look = look["name"]
            self.alpha = _uniform(look, "u_alpha")
            self.beta = _uniform(look, "u_beta")
            self.step = image_step if image_step and image_step > 0 else None
            self.speed = None if self.step is not None else 1.0
            self.scale = _uniform(look, "u_noise_scale")
            self.loop = bool(self._header["loop"]) if self._header["steps"] > 1 else None
            self.hold = False if self._header["steps"] > 1 else None

    @property
    def settings(self):
        """The page's settings now, by name (those it has)."""
        return {name: getattr(self, name) for name in LIVE if getattr(self, name) is not None}

    def set(self, **keys):
        """Set scene keys (docs/scenes.md). The page's own settings go to the
        running page (style, where it is one of the page's styles, to look);
        any other key prepares the scene again, with the page's settings as
        they are now (a style that is not the page's with its own), and the
        page starts again on it. Raises ValueError for a value the scene
        refuses, TypeError for an unknown key."""
        styles = [look["name"] for look in self._header["looks"]]
        keys = dict(keys)
        if keys.get("style") in styles:  # one of the page's styles: its menu
            keys["look"] = keys.pop("style")
        live = {k: keys.pop(k) for k in list(keys) if k in LIVE}
        if keys:
            # The page's settings as they are now, except where a new style
            # brings its own.
            kept = self.settings
            if "style" in keys:
                kept = {"loop": self.loop} if self.loop is not None else {}
            now = {k: v for k, v in {**kept, **live}.items() if k in _KEYS}
            look = now.pop("look", styles[0])
            # The scene's own look is the first ("as rendered" where it is no style's).
            style = {} if look == styles[0] else {"style": look}
            self.animation.set(**{**style, **now, **keys})  # raises before anything changes
            self._send_scene()
            live = {k: v for k, v in live.items() if k not in _KEYS}
        for name, value in live.items():
            setattr(self, name, value)

    # ---- the settings' checks, for values from Python and from the page
    def _range(self, name):
        r = self._header.get("ranges", {}).get(name)
        return (r["min"], r["max"]) if r else (None, None)

    @traitlets.validate(*_NUMBERS)
    def _check_number(self, proposal):
        name, value = proposal["trait"].name, proposal["value"]
        if value is None:
            return value
        if value != value or value in (float("inf"), float("-inf")):
            raise SettingError(f"{name}: {value} is not a number the page can take")
        lo, hi = self._range(name) if name != "speed" else (0.0, 4.0)
        if (lo is not None and value < lo) or (hi is not None and value > hi):
            raise SettingError(f"{name}: {value} is outside {lo}..{hi}")
        return value

    @traitlets.validate("look")
    def _check_look(self, proposal):
        value = proposal["value"]
        names = [look["name"] for look in self._header.get("looks", [])]
        if value is not None and names and value not in names:
            raise SettingError(f"look: {value!r} is not one of this page's styles "
                               f"({', '.join(names)}); set(style=...) prepares another")
        return value

    @traitlets.validate("loop", "hold")
    def _check_series(self, proposal):
        if proposal["value"] is not None and self._header.get("steps", 1) < 2:
            raise SettingError(f"{proposal['trait'].name}: this scene has one time step")
        return proposal["value"]
