#include "abbe/report/toolpath_view.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "abbe/report/palette.hpp"
#include "abbe/report/svg.hpp"

namespace abbe::report {
namespace {

// Draws, rotates, zooms and picks; one instance per figure.toolpath-3d.
// Colours: keep in step with palette::tolerance_colour.
constexpr const char* kScript = R"JS(
(function () {
  function lerp(a, b, f) {
    var c = [];
    for (var k = 0; k < 3; k++) c.push(Math.round(a[k] + f * (b[k] - a[k])));
    return 'rgb(' + c.join(',') + ')';
  }
  var NB = 24;  // colour bins per band
  function binColour(b) {  // b: 0..NB-1 within, NB..2NB-1 above, 2NB over 2x, 2NB+1 unknown
    if (b < NB) return lerp([198, 219, 239], [8, 48, 107], b / (NB - 1));
    if (b < 2 * NB) return lerp([230, 159, 0], [213, 94, 0], (b - NB) / (NB - 1));
    return b === 2 * NB ? '#7f2704' : '#999999';
  }
  function bin(r) {
    if (!(r >= 0)) return 2 * NB + 1;
    if (r <= 1) return Math.min(NB - 1, Math.floor(r * NB));
    if (r <= 2) return NB + Math.min(NB - 1, Math.floor((r - 1) * NB));
    return 2 * NB;
  }
  function fmt(v, n) { return v === null || !isFinite(v) ? 'n/a' : v.toFixed(n); }

  function View(fig) {
    var t0 = performance.now();
    var id = fig.id;
    var data = JSON.parse(document.getElementById(id + '-data').textContent);
    var canvas = fig.querySelector('canvas');
    var tip = fig.querySelector('.tip');
    var tolIn = document.getElementById(id + '-tol');
    var kIn = document.getElementById(id + '-k');
    var modelIn = document.getElementById(id + '-model');
    var summary = document.getElementById(id + '-above');
    var n = data.p.length / 3;
    var W = canvas.clientWidth || 900, H = canvas.clientHeight || 600;
    var dpr = window.devicePixelRatio || 1;
    canvas.width = Math.round(W * dpr);
    canvas.height = Math.round(H * dpr);
    var ctx = canvas.getContext('2d');
    var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (var i = 0; i < n; i++)
      for (var a = 0; a < 3; a++) {
        lo[a] = Math.min(lo[a], data.p[3 * i + a]);
        hi[a] = Math.max(hi[a], data.p[3 * i + a]);
      }
    var centre = [0, 0, 0], extent = 0;
    for (a = 0; a < 3; a++) {
      centre[a] = n ? (lo[a] + hi[a]) / 2 : 0;
      extent = Math.max(extent, n ? hi[a] - lo[a] : 0);
    }
    if (!(extent > 0)) extent = 1;
    var presets = {
      iso: [-135, 35.264], xy: [0, 90], xz: [0, 0], yz: [-90, 0]
    };
    var state = {yaw: presets.iso[0], pitch: presets.iso[1], zoom: 1, hover: -1, draws: 0};
    var sx = new Float64Array(n), sy = new Float64Array(n);  // drawn (nominal + K d)
    var nx = new Float64Array(n), ny = new Float64Array(n);  // nominal
    var mags = [];
    for (var m = 0; m < data.models.length; m++) {
      var mg = new Float64Array(n), d = data.d[m];
      for (i = 0; i < n; i++) {
        var dx = d[3 * i], dy = d[3 * i + 1], dz = d[3 * i + 2];
        mg[i] = dx === null || dy === null || dz === null ? -1 : Math.sqrt(dx * dx + dy * dy + dz * dz);
      }
      mags.push(mg);
    }
    function num(input, fallback) {
      var v = parseFloat(input.value);
      return isFinite(v) && v >= 0 ? v : fallback;
    }
    function project() {
      var m = modelIn.selectedIndex, d = data.d[m], k = num(kIn, data.k) * 1e-3;
      var cy = Math.cos(state.yaw * Math.PI / 180), sy_ = Math.sin(state.yaw * Math.PI / 180);
      var cp = Math.cos(state.pitch * Math.PI / 180), sp = Math.sin(state.pitch * Math.PI / 180);
      var s = 0.85 * Math.min(W, H) / extent * state.zoom;
      for (var i = 0; i < n; i++) {
        var q = [0, 0, 0], p = [0, 0, 0];
        for (var a = 0; a < 3; a++) {
          var e = d[3 * i + a];
          p[a] = data.p[3 * i + a] - centre[a];
          q[a] = p[a] + (e === null ? 0 : k * e);
        }
        var x1 = q[0] * cy - q[1] * sy_, y1 = q[0] * sy_ + q[1] * cy;
        sx[i] = W / 2 + s * x1;
        sy[i] = H / 2 - s * (y1 * sp + q[2] * cp);
        x1 = p[0] * cy - p[1] * sy_;
        y1 = p[0] * sy_ + p[1] * cy;
        nx[i] = W / 2 + s * x1;
        ny[i] = H / 2 - s * (y1 * sp + p[2] * cp);
      }
    }
    function axes() {
      var cy = Math.cos(state.yaw * Math.PI / 180), sy_ = Math.sin(state.yaw * Math.PI / 180);
      var cp = Math.cos(state.pitch * Math.PI / 180), sp = Math.sin(state.pitch * Math.PI / 180);
      var names = ['X', 'Y', 'Z'], ox = 50, oy = H - 50;
      ctx.lineWidth = 1.5;
      ctx.font = '13px sans-serif';
      for (var a = 0; a < 3; a++) {
        var q = [0, 0, 0];
        q[a] = 1;
        var x1 = q[0] * cy - q[1] * sy_, y1 = q[0] * sy_ + q[1] * cy;
        var px = ox + 32 * x1, py = oy - 32 * (y1 * sp + q[2] * cp);
        ctx.strokeStyle = ctx.fillStyle = '#333';
        ctx.beginPath();
        ctx.moveTo(ox, oy);
        ctx.lineTo(px, py);
        ctx.stroke();
        ctx.fillText(names[a], px + 3, py - 3);
      }
    }
    function draw() {
      var t = performance.now();
      project();
      var m = modelIn.selectedIndex, mg = mags[m], tol = num(tolIn, data.tol);
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.fillStyle = '#ffffff';
      ctx.fillRect(0, 0, W, H);
      var bins = [], above = 0;
      for (var b = 0; b <= 2 * NB + 1; b++) bins.push([]);
      for (var i = 0; i < n; i++) {
        var r = tol > 0 ? mg[i] / tol : (mg[i] > 0 ? Infinity : 0);
        if (r > 1) above++;
        if (i > 0) bins[bin(r)].push(i);
      }
      if (num(kIn, data.k) > 0 && n > 1) {  // the nominal path, dashed grey
        ctx.strokeStyle = '#888888';
        ctx.lineWidth = 1;
        ctx.setLineDash([4, 4]);
        ctx.beginPath();
        ctx.moveTo(nx[0], ny[0]);
        for (i = 1; i < n; i++) ctx.lineTo(nx[i], ny[i]);
        ctx.stroke();
        ctx.setLineDash([]);
      }
      ctx.lineWidth = 1.6;
      ctx.lineCap = 'round';
      for (b = 0; b < bins.length; b++) {
        if (!bins[b].length) continue;
        ctx.strokeStyle = binColour(b);
        ctx.beginPath();
        for (var j = 0; j < bins[b].length; j++) {
          var k = bins[b][j];
          ctx.moveTo(sx[k - 1], sy[k - 1]);
          ctx.lineTo(sx[k], sy[k]);
        }
        ctx.stroke();
      }
      if (n === 1) {
        ctx.fillStyle = binColour(bin(mg[0] / tol));
        ctx.fillRect(sx[0] - 2, sy[0] - 2, 4, 4);
      }
      if (state.hover >= 0) {
        ctx.strokeStyle = '#000';
        ctx.lineWidth = 2;
        ctx.beginPath();
        ctx.arc(sx[state.hover], sy[state.hover], 6, 0, 2 * Math.PI);
        ctx.stroke();
      }
      axes();
      state.draws++;
      summary.textContent = above + ' of ' + n + ' drawn points above ' + tol + ' \u00b5m (' +
        data.models[m] + ')';
      fig.dataset.yaw = state.yaw.toFixed(1);
      fig.dataset.pitch = state.pitch.toFixed(1);
      fig.dataset.zoom = state.zoom.toFixed(3);
      fig.dataset.hover = state.hover;
      fig.dataset.draws = state.draws;
      fig.dataset.above = above;
      fig.dataset.drawMs = (performance.now() - t).toFixed(1);
    }
    function hoverText(i) {
      var m = modelIn.selectedIndex, d = data.d[m], line = data.line[i];
      var src = data.src[String(line)] || '';
      return 'line ' + line + ': ' + src + '\nP = (' + fmt(data.p[3 * i], 3) + ', ' +
        fmt(data.p[3 * i + 1], 3) + ', ' + fmt(data.p[3 * i + 2], 3) + ') mm\n' +
        data.models[m] + ': d = (' + fmt(d[3 * i], 3) + ', ' + fmt(d[3 * i + 1], 3) + ', ' +
        fmt(d[3 * i + 2], 3) + ') \u00b5m, |d| = ' + (mags[m][i] < 0 ? 'n/a' : fmt(mags[m][i], 3)) + ' \u00b5m';
    }
    function pick(x, y) {
      var best = -1, bd = 100;  // within 10 px
      for (var i = 0; i < n; i++) {
        var ex = sx[i] - x, ey = sy[i] - y, e = ex * ex + ey * ey;
        if (e < bd) { bd = e; best = i; }
      }
      return best;
    }
    function setHover(i, x, y) {
      if (i === state.hover && i < 0) return;
      state.hover = i;
      if (i < 0) {
        tip.style.display = 'none';
        tip.textContent = '';
      } else {
        tip.textContent = hoverText(i);
        tip.style.display = 'block';
        tip.style.left = Math.min(x + 14, W - 320) + 'px';
        tip.style.top = (y + 14) + 'px';
      }
      draw();
    }
    var drag = null;
    canvas.addEventListener('mousedown', function (e) {
      drag = {x: e.clientX, y: e.clientY, yaw: state.yaw, pitch: state.pitch};
      e.preventDefault();
    });
    window.addEventListener('mouseup', function () { drag = null; });
    canvas.addEventListener('mousemove', function (e) {
      var r = canvas.getBoundingClientRect(), x = e.clientX - r.left, y = e.clientY - r.top;
      if (drag) {
        state.yaw = drag.yaw - (e.clientX - drag.x) * 0.5;
        state.pitch = Math.max(-90, Math.min(90, drag.pitch + (e.clientY - drag.y) * 0.5));
        state.hover = -1;
        tip.style.display = 'none';
        draw();
      } else {
        setHover(pick(x, y), x, y);
      }
    });
    canvas.addEventListener('mouseleave', function () { if (!drag) setHover(-1, 0, 0); });
    canvas.addEventListener('wheel', function (e) {
      state.zoom = Math.max(0.1, Math.min(200, state.zoom * Math.exp(-e.deltaY * 0.002)));
      e.preventDefault();
      draw();
    }, {passive: false});
    fig.querySelectorAll('button[data-view]').forEach(function (b) {
      b.addEventListener('click', function () {
        var v = b.getAttribute('data-view');
        if (v === 'in') state.zoom *= 1.5;
        else if (v === 'out') state.zoom /= 1.5;
        else { state.yaw = presets[v][0]; state.pitch = presets[v][1]; state.zoom = 1; }
        state.hover = -1;
        tip.style.display = 'none';
        draw();
      });
    });
    [tolIn, kIn, modelIn].forEach(function (el) { el.addEventListener('input', draw); });
    this.project = function (i) {  // client coordinates of drawn point i
      var r = canvas.getBoundingClientRect();
      return [r.left + sx[i], r.top + sy[i]];
    };
    this.count = n;
    this.largest = function () {  // the drawn point of the largest |d| of the chosen model
      var mg = mags[modelIn.selectedIndex], best = 0;
      for (var i = 1; i < n; i++) if (mg[i] > mg[best]) best = i;
      return best;
    };
    draw();
    fig.dataset.ready = 'true';
    fig.dataset.initMs = (performance.now() - t0).toFixed(1);
  }
  window.abbeViews = window.abbeViews || {};
  document.querySelectorAll('figure.toolpath-3d').forEach(function (f) {
    window.abbeViews[f.id] = new View(f);
  });
})();
)JS";

constexpr const char* kStyle = R"(<style>
figure.toolpath-3d { margin: 8px 0; }
figure.toolpath-3d .stage { position: relative; width: 900px; height: 600px; }
figure.toolpath-3d canvas { width: 900px; height: 600px; border: 1px solid #ddd; background: #fff; cursor: grab; display: block; }
figure.toolpath-3d .tip { position: absolute; display: none; white-space: pre; background: #fffff0; border: 1px solid #888; padding: 4px 6px; font-size: 12px; pointer-events: none; }
figure.toolpath-3d .controls { font-size: 13px; margin: 6px 0; }
figure.toolpath-3d .controls input[type=number] { width: 6em; }
figure.toolpath-3d .scale span { display: inline-block; width: 90px; height: 12px; vertical-align: middle; }
</style>
)";

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  std::string s = fmt::format("{:.3f}", v);
  // Trim trailing zeros ("1.500" → "1.5", "2.000" → "2").
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::string json_string(const std::string& s) {
  std::string j = nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string o;
  o.reserve(j.size());
  for (char c : j) o += c == '<' ? std::string("\\u003c") : std::string(1, c);
  return o;
}

// Rounded up to two significant digits (19.785 → 20, 0.1234 → 0.13).
double round_up_2(double v) {
  const double mag = std::pow(10.0, std::floor(std::log10(v)) - 1.0);
  return std::ceil(v / mag - 1e-9) * mag;
}

}  // namespace

double auto_tolerance(const PredictedPath& r) {
  double m = 0.0;
  for (const auto& s : r.stats)
    if (std::isfinite(s.max_um)) m = std::max(m, s.max_um);
  return m > 0.0 ? round_up_2(m) : 1.0;
}

std::string toolpath_view_json(const PredictedPath& r, const ToolpathViewOptions& o) {
  const double tol = o.tolerance_um > 0.0 ? o.tolerance_um : auto_tolerance(r);
  std::string s = fmt::format("{{\"k\":{},\"tol\":{},\"models\":[", num(o.exaggerate), num(tol));
  for (std::size_t m = 0; m < r.models.size(); ++m)
    s += (m ? "," : "") + json_string(model::to_string(r.models[m]));
  s += "],\"p\":[";
  for (std::size_t i = 0; i < r.nominal.size(); ++i)
    s += fmt::format("{}{},{},{}", i ? "," : "", num(r.nominal[i].x()), num(r.nominal[i].y()),
                     num(r.nominal[i].z()));
  s += "],\"line\":[";
  for (std::size_t i = 0; i < r.line.size(); ++i) s += fmt::format("{}{}", i ? "," : "", r.line[i]);
  s += "],\"d\":[";
  for (std::size_t m = 0; m < r.deviation_um.size(); ++m) {
    s += m ? ",[" : "[";
    const auto& d = r.deviation_um[m];
    for (std::size_t i = 0; i < d.size(); ++i)
      s += fmt::format("{}{},{},{}", i ? "," : "", num(d[i].x()), num(d[i].y()), num(d[i].z()));
    s += "]";
  }
  s += "],\"src\":{";
  bool first = true;
  for (const auto& [line, text] : r.source) {
    s += fmt::format("{}\"{}\":{}", first ? "" : ",", line, json_string(text));
    first = false;
  }
  s += "}}";
  return s;
}

std::string render_toolpath_view(const PredictedPath& r, const ToolpathViewOptions& o) {
  const double tol = o.tolerance_um > 0.0 ? o.tolerance_um : auto_tolerance(r);
  const std::string id = escape_xml(o.id);
  std::string h = kStyle;
  h += fmt::format("<figure class=\"toolpath-3d\" id=\"{}\">\n<div class=\"controls\">", id);
  h += fmt::format(
      "view <button data-view=\"iso\">isometric</button> <button data-view=\"xy\">XY</button> "
      "<button data-view=\"xz\">XZ</button> <button data-view=\"yz\">YZ</button> "
      "<button data-view=\"in\">+</button> <button data-view=\"out\">&#8722;</button> "
      "&#183; model <select id=\"{0}-model\">",
      id);
  for (std::size_t m = 0; m < r.models.size(); ++m)
    h += fmt::format("<option>{}</option>", escape_xml(model::to_string(r.models[m])));
  h += fmt::format(
      "</select> &#183; tolerance <input type=\"number\" id=\"{0}-tol\" min=\"0\" step=\"any\" "
      "value=\"{1}\"> &#181;m &#183; deviation &#215; <input type=\"number\" id=\"{0}-k\" "
      "min=\"0\" step=\"any\" value=\"{2}\"></div>\n",
      id, num(tol), num(o.exaggerate));
  h += fmt::format(
      "<div class=\"stage\"><canvas width=\"900\" height=\"600\" aria-label=\"3-D toolpath\">"
      "</canvas><div class=\"tip\" id=\"{}-tip\"></div></div>\n",
      id);
  h += fmt::format(
      "<figcaption class=\"scale\">|d| against the tolerance: "
      "<span style=\"background: linear-gradient(to right, {}, {})\"></span> 0 &#8230; 1 &#215; "
      "tolerance, <span style=\"background: linear-gradient(to right, {}, {})\"></span> 1 &#8230; "
      "2 &#215;, <span style=\"background: {}; width: 20px\"></span> above 2 &#215; &#183; "
      "<span id=\"{}-above\" style=\"width: auto; height: auto\"></span></figcaption>\n",
      palette::tolerance_colour(0.0), palette::tolerance_colour(1.0),
      palette::tolerance_colour(1.0001), palette::tolerance_colour(2.0),
      palette::tolerance_colour(3.0), id);
  h += fmt::format("<script type=\"application/json\" id=\"{}-data\">{}</script>\n", id,
                   toolpath_view_json(r, o));
  h += "<script>";
  h += kScript;
  h += "</script>\n</figure>\n";
  return h;
}

}  // namespace abbe::report
