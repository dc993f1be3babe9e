/* EmboTeam report pages: helpers shared by the episode viewer and the benchmark index.
   Plain ES2017, no dependencies, nothing fetched: the pages must work from file://.
   Data is only ever inserted with textContent / setAttribute, never as HTML. */
"use strict";
var ET = (function () {
  var SVGNS = "http://www.w3.org/2000/svg";

  function setAttrs(e, attrs) {
    if (!attrs) return;
    Object.keys(attrs).forEach(function (k) {
      var v = attrs[k];
      if (v === null || v === undefined || v === false) return;
      if (k === "class") e.setAttribute("class", v);
      else e.setAttribute(k, v === true ? "" : String(v));
    });
  }

  /** An HTML element, appended to parent if given; text is set as textContent. */
  function el(tag, attrs, parent, text) {
    var e = document.createElement(tag);
    setAttrs(e, attrs);
    if (text !== undefined && text !== null) e.textContent = String(text);
    if (parent) parent.appendChild(e);
    return e;
  }

  /** An SVG element. */
  function svg(tag, attrs, parent, text) {
    var e = document.createElementNS(SVGNS, tag);
    setAttrs(e, attrs);
    if (text !== undefined && text !== null) e.textContent = String(text);
    if (parent) parent.appendChild(e);
    return e;
  }

  /** Index of the last element of sorted arr that is <= t; -1 if none. O(log n). */
  function lastLE(arr, t) {
    var lo = 0, hi = arr.length - 1, ans = -1;
    while (lo <= hi) {
      var mid = (lo + hi) >> 1;
      if (arr[mid] <= t) { ans = mid; lo = mid + 1; } else { hi = mid - 1; }
    }
    return ans;
  }

  function num(v, digits) {
    if (v === null || v === undefined || Number.isNaN(v)) return "–";
    return Number(v).toFixed(digits === undefined ? 2 : digits);
  }

  function pct(v) {
    if (v === null || v === undefined || Number.isNaN(v)) return "–";
    return (100 * v).toFixed(v >= 0.9995 || v === 0 ? 0 : 1) + "%";
  }

  /** Seconds as "12.3 s" or "2:05.4". */
  function secs(s) {
    if (s === null || s === undefined || Number.isNaN(s)) return "–";
    if (s < 60) return s.toFixed(1) + " s";
    var m = Math.floor(s / 60);
    var r = s - 60 * m;
    return m + ":" + (r < 10 ? "0" : "") + r.toFixed(1);
  }

  /** A tick step of 1, 2 or 5 times a power of ten giving about `target` ticks. */
  function niceStep(range, target) {
    var raw = range / Math.max(1, target);
    var p = Math.pow(10, Math.floor(Math.log10(raw)));
    var m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }

  var tip = null;
  /** Show the shared tooltip near (x, y) with one line per entry of `lines`. */
  function showTip(lines, x, y) {
    if (!tip) tip = document.getElementById("tooltip");
    if (!tip) return;
    tip.textContent = "";
    lines.forEach(function (line, i) { el("div", { class: i === 0 ? "tip-head" : "tip-line" }, tip, line); });
    tip.hidden = false;
    var w = tip.offsetWidth, h = tip.offsetHeight;
    var left = Math.min(x + 14, window.innerWidth - w - 8);
    var top = y + 16 + h > window.innerHeight ? y - h - 10 : y + 16;
    tip.style.left = Math.max(4, left) + "px";
    tip.style.top = Math.max(4, top) + "px";
  }

  function hideTip() {
    if (!tip) tip = document.getElementById("tooltip");
    if (tip) tip.hidden = true;
  }

  /** The JSON payload of <script type="application/json" id=...>. */
  function data(id) {
    return JSON.parse(document.getElementById(id).textContent);
  }

  return { el: el, svg: svg, lastLE: lastLE, num: num, pct: pct, secs: secs, niceStep: niceStep,
           showTip: showTip, hideTip: hideTip, data: data };
})();
