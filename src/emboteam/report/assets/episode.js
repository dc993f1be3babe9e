/* EmboTeam episode viewer. Reads the JSON embedded in #episode-data (built by
   emboteam.report.episode_report) and draws the map, Gantt chart, behavior tree, event
   timeline and details; one clock (the scrubber) drives them all.
   Per frame every panel does O(log n) lookups and touches only what changed, so traces
   of many thousands of events stay responsive. */
(function () {
  "use strict";
  var el = ET.el, svg = ET.svg, lastLE = ET.lastLE;
  var D = ET.data("episode-data");
  var TL = D.timeline;
  var END = Math.max(TL.end, 1e-3);
  var COLORS = D.colors;

  var OUTCOME_COLORS = {
    success: "#3a9b5c", unfinished: "#aeb6bf",
    actuation_fault: "#d64541", not_visible: "#f28e2b", spot_busy: "#e0b400",
    not_reachable: "#ff8c9a", robot_down: "#5a2a82", held_by_other: "#b35c1e"
  };
  // precondition failures (hand full, receptacle closed, no knife, ...): dark shades, one
  // per reason present in this episode, so the legend can tell them apart
  var OTHER_FAILURES = ["#8e2b2b", "#6b2d5c", "#a0522d", "#b03a48", "#5e3a2a", "#804d8c", "#7a4a1e", "#993d5e"];
  (function () {
    var others = {};
    TL.actions.forEach(function (a) { if (a.outcome === "failed" && !(a.reason in OUTCOME_COLORS)) others[a.reason || "unknown"] = 1; });
    Object.keys(others).sort().forEach(function (r, i) { OUTCOME_COLORS[r] = OTHER_FAILURES[i % OTHER_FAILURES.length]; });
  })();
  var CATEGORY_COLORS = { sync: "#2f7bd8", lock: "#d9822b", blackboard: "#6b7785", recovery: "#b8860b", sim: "#7b3294", replan: "#c2185b" };
  var CATEGORY_LABELS = { sync: "sync flags", lock: "resource locks", blackboard: "other keys", recovery: "recoveries", sim: "simulator", replan: "replans" };
  var CATEGORIES = ["sync", "lock", "blackboard", "recovery", "sim", "replan"];
  var CATEGORY_BADGES = { sync: "sync", lock: "lock", blackboard: "other", recovery: "recovery", sim: "sim", replan: "replan" };

  function barColor(a) {
    if (a.outcome === "success") return OUTCOME_COLORS.success;
    if (a.outcome === "unfinished") return OUTCOME_COLORS.unfinished;
    return OUTCOME_COLORS[a.reason || "unknown"];
  }
  function outcomeKey(a) { return a.outcome === "failed" ? "failed:" + (a.reason || "unknown") : a.outcome; }
  function robotColor(r) { return COLORS[r] || "#555"; }
  function shortRobot(r) { var m = /^robot(.+)$/.exec(r); return m ? m[1] : r.slice(0, 2); }
  var SHORT_SKILLS = { GoToObject: "GoTo", PickupObject: "Pick", PutObject: "Put", OpenObject: "Open",
                       CloseObject: "Close", SwitchOn: "On", SwitchOff: "Off", SliceObject: "Slice",
                       BreakObject: "Break", CleanObject: "Clean", ThrowObject: "Throw",
                       DropHandObject: "Drop", PushObject: "Push", PullObject: "Pull" };
  function shortSkill(s) { return SHORT_SKILLS[s] || s.replace(/Object$/, ""); }

  var listeners = [];
  var clock = { t: 0 };
  function setTime(t) {
    clock.t = Math.min(END, Math.max(0, t));
    for (var i = 0; i < listeners.length; i++) listeners[i](clock.t);
  }

  /* ---------------- header ---------------- */
  function buildHeader() {
    var m = D.meta, k = D.metrics;
    document.getElementById("task-title").textContent = m.task;
    var verdict = document.getElementById("verdict");
    verdict.textContent = k.success ? "SUCCESS" : "FAILED";
    verdict.className = "badge " + (k.success ? "ok" : "bad");
    var bits = [m.floor_plan + (m.room ? " (" + m.room.replace("_", " ") + ")" : ""),
                m.robots.length + " robot" + (m.robots.length === 1 ? "" : "s") + ": " + m.robots.join(", "),
                "mode " + m.mode, "front end " + m.frontend, "seed " + m.seed];
    if (m.category) bits.splice(1, 0, m.category);
    if (m.fault_level) bits.push("faults " + m.fault_level);
    if (m.disturbance) bits.push("disturbance " + m.disturbance.spec);
    document.getElementById("meta-line").textContent = bits.join(" · ");
    document.getElementById("instruction").textContent = m.instruction;
    if (m.error) {
      var b = document.getElementById("error-banner");
      b.hidden = false;
      b.textContent = "Episode ended with an error: " + m.error;
    }
    if (m.not_attempted && m.not_attempted.length) {   // requested, but the planner could not plan it
      var na = document.getElementById("error-banner");
      na.hidden = false;
      na.textContent = (m.error ? na.textContent + " " : "") + "Not attempted (the planner could not plan it): " +
        m.not_attempted.map(function (n) { return n.condition + " (" + n.reason + ")"; }).join("; ");
    }
    if (m.notes && m.notes.length) {     // spans the front end did not read, or read with doubt
      var notes = document.getElementById("reading-notes");
      notes.hidden = false;
      m.notes.forEach(function (n) { el("li", {}, notes, n); });
    }
    if (m.unexplained && m.unexplained.length) {   // named things that ended in no goal, unexplained
      var un = document.getElementById("reading-notes");
      un.hidden = false;
      el("li", {}, un, "unexplained: " + m.unexplained.join(", ") + " (named, but in no goal)");
    }
    if (m.candidates && m.candidates.length > 1) {   // the readings considered, best first, with scores
      var cands = document.getElementById("reading-candidates");
      cands.hidden = false;
      m.candidates.forEach(function (c, k) {
        var how = c.resolves.map(function (r) { return r.how; }).join("; ");
        el("li", { class: k === 0 ? "chosen" : null, title: c.goals.join(" & ") }, cands,
           c.score.toFixed(2) + "  " + c.sentence + (how ? "  [" + how + "]" : ""));
      });
    }
    var box = document.getElementById("metrics");
    function card(label, value, cls, title) {
      var c = el("div", { class: "metric", title: title || null }, box);
      el("div", { class: "label" }, c, label);
      el("div", { class: "value " + (cls || "") }, c, value);
    }
    var dist = m.disturbance;   // bench --breakdown/--join/--moves/--msg-*: what happened, the ceiling
    if (dist) {
      var db = document.getElementById("disturbance-banner");
      db.hidden = false;
      var what = dist.events.map(function (e) { return e.kind + " " + e.detail + " at " + e.t.toFixed(1) + " s"; });
      Object.keys(dist.network || {}).forEach(function (k) { what.push(dist.network[k] + " " + k.replace(/_/g, " ")); });
      db.textContent = "Disturbance " + dist.spec + ": " + (what.length ? what.join("; ") : "none happened before the end") +
        ". Ceiling: " + (dist.savable === true ? "savable" : dist.savable === false ? "unsavable" : "unknown") +
        " (" + dist.ceiling + ")" + (dist.joined.length ? ". Joined: " + dist.joined.join(", ") + ", " + dist.joiner_actions + " action(s) carried out" : "") +
        (dist.wall_after !== null ? ". Ended " + dist.wall_after.toFixed(2) + " s (wall) after the disturbance, stop: " + dist.stop_reason : "") + ".";
    }
    card("SR", k.success ? "1" : "0", k.success ? "ok" : "bad", "success: every goal condition holds at the end");
    card("GCR", ET.pct(k.gcr), k.gcr >= 0.9995 ? "ok" : "", "goal-condition recall");
    card("Exec", ET.pct(k.exec), "", "share of executed actions that succeeded");
    card("Makespan", ET.secs(k.makespan), "", "simulated seconds until the last robot stopped");
    card("Actions", k.actions + (k.failed_actions ? " (" + k.failed_actions + " failed)" : ""), "");
    card("Recoveries", String(k.recoveries), "");
    card("Replans", String(k.replans), "");
    card("LLM calls", String(k.llm_calls), "");
    card("Tokens", k.tokens.toLocaleString("en-US"), "");
    card("Plan time", ET.secs(k.plan_seconds), "", "wall-clock seconds in PFG + HP");
  }

  /* ---------------- map ---------------- */
  function buildMap() {
    var box = document.getElementById("map");
    var M = D.map;
    var caption = document.getElementById("map-caption");
    if (!M) {
      el("div", { class: "empty" }, box, D.map_note || "no map for this floor plan");
      return;
    }
    caption.textContent = M.floor_plan + " · top-down, 1 m grid · footprints approximate";
    var S = 100;
    var W = (M.max_x - M.min_x) * S, H = (M.max_z - M.min_z) * S;
    function X(x) { return (x - M.min_x) * S; }
    function Y(z) { return (M.max_z - z) * S; }
    var root = svg("svg", { viewBox: "0 0 " + W.toFixed(1) + " " + H.toFixed(1), role: "img",
                            "aria-label": "Top-down map of " + M.floor_plan }, box);
    svg("rect", { class: "room", x: 1.5, y: 1.5, width: W - 3, height: H - 3, rx: 6 }, root);
    var grid = svg("g", {}, root);
    for (var gx = Math.ceil(M.min_x); gx <= M.max_x; gx++) svg("line", { class: "grid", x1: X(gx), x2: X(gx), y1: 3, y2: H - 3 }, grid);
    for (var gz = Math.ceil(M.min_z); gz <= M.max_z; gz++) svg("line", { class: "grid", y1: Y(gz), y2: Y(gz), x1: 3, x2: W - 3 }, grid);
    // the navigation grid: the 0.25 m cells robots can stand on
    (M.cells || []).forEach(function (c) {
      svg("rect", { class: "nav-cell", x: X(c[0]) - S * 0.11, y: Y(c[1]) - S * 0.11, width: S * 0.22, height: S * 0.22, rx: 2 }, grid);
    });

    var byId = {};
    var objs = svg("g", {}, root);
    var labels = [];
    M.objects.forEach(function (o) {
      var node;
      var hl = o.highlight ? " hl" : "";
      if (o.kind === "furniture" || o.kind === "appliance") {
        node = svg("rect", { class: "obj " + o.kind + hl, x: X(o.x - o.w / 2), y: Y(o.z + o.d / 2),
                             width: o.w * S, height: o.d * S, rx: 3 }, objs);
      } else if (o.kind === "fixture") {
        node = svg("rect", { class: "obj fixture" + hl, x: X(o.x) - 4.5, y: Y(o.z) - 4.5, width: 9, height: 9, rx: 1.5 }, objs);
      } else {
        node = svg("circle", { class: "obj item" + hl, cx: X(o.x), cy: Y(o.z), r: o.highlight ? 6 : 4.5 }, objs);
      }
      node.setAttribute("data-id", o.id);
      byId[o.id] = { o: o, node: node };
      if (o.highlight) labels.push(o);
    });

    // labels of the objects the plan touches; nudged down when two would overlap
    var labelLayer = svg("g", {}, root);
    var placed = [];
    var labelNodes = {};
    labels.forEach(function (o) {
      var lx = X(o.x), ly = Y(o.z) - (o.kind === "item" ? 10 : 0);
      for (var k = 0; k < 6; k++) {
        var clash = placed.some(function (p) { return Math.abs(p[0] - lx) < 60 && Math.abs(p[1] - ly) < 13; });
        if (!clash) break;
        ly += 14;
      }
      placed.push([lx, ly]);
      // keep labels inside the room: anchor them at their end near the right wall
      var half = o.id.length * 3.4;
      var anchor = lx + half > W - 4 ? "end" : lx - half < 4 ? "start" : "middle";
      labelNodes[o.id] = svg("text", { class: "obj-label" + (o.kind === "item" ? " item-label" : ""),
                                       x: anchor === "end" ? Math.min(lx, W - 6) : anchor === "start" ? Math.max(lx, 6) : lx,
                                       y: ly, "text-anchor": anchor }, labelLayer, o.id);
    });

    // scale bar
    var sc = svg("g", { class: "scale" }, root);
    svg("line", { x1: 12, x2: 12 + S, y1: H - 14, y2: H - 14 }, sc);
    svg("text", { x: 12 + S + 6, y: H - 10 }, sc, "1 m");

    // robots: full path (dashed), travelled part (solid), marker
    var pathLayer = svg("g", {}, root);
    var robotLayer = svg("g", {}, root);
    var robots = TL.robots.map(function (r) {
      var tr = TL.poses[r] || { t: [], x: [], z: [], holding: [] };
      var pts = tr.t.map(function (_, i) { return [X(tr.x[i]), Y(tr.z[i])]; });
      var cum = [0];
      for (var i = 1; i < pts.length; i++) cum.push(cum[i - 1] + Math.hypot(pts[i][0] - pts[i - 1][0], pts[i][1] - pts[i - 1][1]));
      var total = cum.length ? cum[cum.length - 1] : 0;
      var ptsText = pts.map(function (p) { return p[0].toFixed(1) + "," + p[1].toFixed(1); }).join(" ");
      var color = robotColor(r);
      var full = svg("polyline", { class: "path-full", points: ptsText, stroke: color }, pathLayer);
      var done = svg("polyline", { class: "path-done", points: ptsText, stroke: color,
                                   "stroke-dasharray": "0 " + (total + 1) }, pathLayer);
      var g = svg("g", { class: "robot", "data-robot": r }, robotLayer);
      svg("circle", { class: "body", r: 15, fill: color }, g);
      svg("text", { class: "num" }, g, shortRobot(r));
      var held = svg("circle", { class: "held", r: 6, cx: 13, cy: -13, visibility: "hidden" }, g);
      var heldLabel = svg("text", { class: "held-label", x: 0, y: 30, visibility: "hidden" }, g);
      g.addEventListener("mousemove", function (ev) {
        var lines = [r];
        if (rs.down) lines.push("broken down");
        if (rs.holding) lines.push("holding " + rs.holding);
        var act = currentAction(r, clock.t);
        if (act) lines.push((act.outcome === "success" ? "" : act.outcome + ": ") + act.action);
        ET.showTip(lines, ev.clientX, ev.clientY);
      });
      g.addEventListener("mouseleave", ET.hideTip);
      var rs = { name: r, tr: tr, pts: pts, cum: cum, total: total, g: g, done: done, full: full,
                 held: held, heldLabel: heldLabel, holding: null, key: "", down: false };
      return rs;
    });

    // objects that move (picked up, put down, thrown): their moves by time
    var moving = {};
    TL.moves.forEach(function (mv) {
      if (!byId[mv.object]) return;
      (moving[mv.object] = moving[mv.object] || { t: [], moves: [], key: "" });
      moving[mv.object].t.push(mv.t);
      moving[mv.object].moves.push(mv);
    });
    var movingIds = Object.keys(moving);

    function poseAt(rs, t) {
      var tr = rs.tr, n = tr.t.length;
      if (!n) return null;
      var i = lastLE(tr.t, t);
      if (i < 0) return { x: rs.pts[0][0], y: rs.pts[0][1], len: 0, holding: tr.holding[0] };
      if (i >= n - 1) return { x: rs.pts[n - 1][0], y: rs.pts[n - 1][1], len: rs.total, holding: tr.holding[n - 1] };
      var t0 = tr.t[i], t1 = tr.t[i + 1];
      var f = t1 > t0 ? (t - t0) / (t1 - t0) : 1;
      var a = rs.pts[i], b = rs.pts[i + 1];
      return { x: a[0] + f * (b[0] - a[0]), y: a[1] + f * (b[1] - a[1]),
               len: rs.cum[i] + f * (rs.cum[i + 1] - rs.cum[i]), holding: tr.holding[i] };
    }

    function jitter(id) {
      var h = 0;
      for (var i = 0; i < id.length; i++) h = (h * 31 + id.charCodeAt(i)) >>> 0;
      return [((h % 17) - 8) * 1.6, (((h >> 5) % 17) - 8) * 1.6];
    }

    // where robots waited for each other, re-planned their drive or stepped aside: shown
    // from the moment it happened
    var NAV_MARKS = { "nav-wait": "waited", "nav-replan": "re-planned", "nav-yield": "stepped aside" };
    var navLayer = svg("g", {}, root);
    var navMarks = [];
    var byName = {};
    robots.forEach(function (rs) { byName[rs.name] = rs; });
    TL.events.forEach(function (e) {
      if (e.category !== "sim" || !(e.key in NAV_MARKS)) return;
      var who = String(e.value || "").split(" ")[0];
      var rs = byName[who];
      var p = rs ? poseAt(rs, e.t) : null;
      if (!p) return;
      var mark = svg("circle", { class: "nav-mark " + e.key, cx: p.x, cy: p.y, r: 6, visibility: "hidden" }, navLayer);
      var label = who + " " + NAV_MARKS[e.key] + " at " + ET.secs(e.t) + " (" + e.value + ")";
      mark.addEventListener("mousemove", function (ev) { ET.showTip([label], ev.clientX, ev.clientY); });
      mark.addEventListener("mouseleave", ET.hideTip);
      navMarks.push({ t: e.t, node: mark });
    });

    // a robot that broke down is drawn greyed out from then on
    var downAt = {};
    TL.events.forEach(function (e) {
      if (e.category !== "sim" || e.key !== "breakdown") return;
      var who = e.robot || e.value;
      if (!(who in downAt)) downAt[who] = e.t;
    });
    function update(t) {
      navMarks.forEach(function (m) { m.node.setAttribute("visibility", t >= m.t ? "visible" : "hidden"); });
      robots.forEach(function (rs) {
        var p = poseAt(rs, t);
        if (!p) { rs.g.setAttribute("visibility", "hidden"); return; }
        var down = rs.name in downAt && t >= downAt[rs.name];
        if (down !== rs.down) { rs.down = down; rs.g.classList.toggle("down", down); }
        rs.g.setAttribute("transform", "translate(" + p.x.toFixed(1) + "," + p.y.toFixed(1) + ")");
        rs.done.setAttribute("stroke-dasharray", p.len.toFixed(1) + " " + (rs.total + 1).toFixed(1));
        var holding = p.holding || null;
        if (holding !== rs.holding) {
          rs.holding = holding;
          rs.held.setAttribute("visibility", holding ? "visible" : "hidden");
          rs.heldLabel.setAttribute("visibility", holding ? "visible" : "hidden");
          rs.heldLabel.textContent = holding || "";
        }
      });
      for (var k = 0; k < movingIds.length; k++) {
        var id = movingIds[k], mv = moving[id], item = byId[id];
        var i = lastLE(mv.t, t);
        var m = i >= 0 ? mv.moves[i] : null;
        var x = X(item.o.x), y = Y(item.o.z), hidden = false;
        if (m && m.robot) { hidden = true; }
        else if (m && m.gone) { hidden = true; }
        else if (m && m.at && byId[m.at]) { var r = byId[m.at].o, j = jitter(id); x = X(r.x) + j[0]; y = Y(r.z) + j[1]; }
        else if (m && m.x !== null && m.x !== undefined) { x = X(m.x); y = Y(m.z); }
        var key = hidden ? "h" : x.toFixed(1) + "," + y.toFixed(1);
        if (key === mv.key) continue;
        mv.key = key;
        var node = item.node;
        node.setAttribute("visibility", hidden ? "hidden" : "visible");
        if (node.tagName === "circle") { node.setAttribute("cx", x); node.setAttribute("cy", y); }
        else { node.setAttribute("x", x - Number(node.getAttribute("width")) / 2); node.setAttribute("y", y - Number(node.getAttribute("height")) / 2); }
        var lab = labelNodes[id];
        if (lab) { lab.setAttribute("visibility", hidden ? "hidden" : "visible"); lab.setAttribute("x", x); lab.setAttribute("y", y - 10); lab.setAttribute("text-anchor", "middle"); }
      }
    }
    listeners.push(update);

    root.addEventListener("mousemove", function (ev) {
      var id = ev.target.getAttribute && ev.target.getAttribute("data-id");
      if (!id) { if (!ev.target.closest(".robot")) ET.hideTip(); return; }
      var o = byId[id].o;
      var lines = [o.id, o.type + " · " + o.kind];
      if (o.parent) lines.push("starts in/on " + o.parent);
      ET.showTip(lines, ev.clientX, ev.clientY);
    });
    root.addEventListener("mouseleave", ET.hideTip);

    mapFocus = function (ids) {
      root.querySelectorAll(".focus").forEach(function (n) { n.classList.remove("focus"); });
      (ids || []).forEach(function (id) { if (byId[id]) byId[id].node.classList.add("focus"); });
    };

    var legend = document.getElementById("map-legend");
    TL.robots.forEach(function (r) {
      var it = el("span", { class: "item" }, legend);
      el("span", { class: "swatch round", style: "background:" + robotColor(r) }, it);
      el("span", {}, it, r);
    });
    [["furniture", "#e9e4d8", "furniture"], ["appliance", "#dde8f3", "appliances"], ["fixture", "#c7ccd2", "switches, knobs, windows"],
     ["item", "#7b8794", "objects (hover for names)"], ["hl", "#d9822b", "objects the plan uses"]]
      .concat(Object.keys(downAt).length ? [["down", "#555", "robot broken down"]] : []).forEach(function (e) {
      var it = el("span", { class: "item" }, legend);
      el("span", { class: "swatch" + (e[0] === "item" || e[0] === "hl" || e[0] === "down" ? " round" : ""), style: "background:" + e[1] }, it);
      el("span", {}, it, e[2]);
    });
  }
  var mapFocus = function () {};

  /* ---------------- Gantt ---------------- */
  var actionsByRobot = {};
  TL.robots.forEach(function (r) { actionsByRobot[r] = { starts: [], bars: [], idx: [] }; });
  TL.actions.forEach(function (a, i) {
    var list = actionsByRobot[a.robot];
    list.starts.push(a.start);
    list.bars.push(a);
    list.idx.push(i);
  });
  function currentAction(robot, t) {
    var list = actionsByRobot[robot];
    if (!list) return null;
    var i = lastLE(list.starts, t);
    if (i < 0) return null;
    var a = list.bars[i];
    return t <= a.end ? a : null;
  }

  function syncEdges() {
    var byStep = {};
    TL.actions.forEach(function (a) { if (a.step) (byStep[a.step] = byStep[a.step] || []).push(a); });
    var edges = [];
    ((D.plan && D.plan.sync) || []).forEach(function (s) {
      var p = byStep[s.producer], c = byStep[s.consumer];
      if (!p || !c) return;
      var okP = p.filter(function (a) { return a.outcome === "success"; });
      var from = (okP.length ? okP : p)[(okP.length ? okP : p).length - 1];
      edges.push({ from: from, to: c[0], reason: s.reason, producer: s.producer, consumer: s.consumer });
    });
    return edges;
  }

  // what caused a replan, in a few words: a breakdown, a joiner, the plan ending, a lost step
  function replanCause(reason) {
    if (!reason) return "";
    var m = /(\S+) is down/.exec(reason) || /(\S+) broke down/.exec(reason);
    if (m) return ": " + m[1] + " down";
    m = /^(.+) joined$/.exec(reason);
    if (m) return ": " + m[1] + " joined";
    if (/goal unmet/.test(reason)) return ": goal unmet";
    if (/^stalled/.test(reason)) return ": stalled";
    return ": " + (reason.length > 28 ? reason.slice(0, 27) + "…" : reason);
  }

  // The first of ``texts`` that fits ``room`` pixels, else no label (false): a label never
  // runs out of its bar into the next one; the bar's tooltip has the whole text.
  function fitLabel(node, texts, room) {
    for (var i = 0; i < texts.length; i++) {
      node.textContent = texts[i];
      var len = node.getComputedTextLength ? node.getComputedTextLength() : 0;
      if (!len) len = texts[i].length * 6;  // not laid out (a hidden panel): estimate
      if (len <= room) return true;
    }
    node.remove();
    return false;
  }

  // Labels that would overlap one drawn before them are hidden (their marker's tooltip
  // says it all): bar labels first, then replans, then disturbances.
  function declutter(labels) {
    var kept = [];
    labels.forEach(function (t) {
      if (!t.isConnected) return;
      var b = t.getBBox();
      if (!b.width) return;
      var hit = kept.some(function (k) {
        return b.x < k.x + k.width + 3 && k.x < b.x + b.width + 3 && b.y < k.y + k.height && k.y < b.y + b.height;
      });
      if (hit) t.setAttribute("display", "none");
      else kept.push(b);
    });
  }

  function buildGantt() {
    var box = document.getElementById("gantt");
    var robots = TL.robots;
    var edges = syncEdges();
    var markers = TL.events.filter(function (e) { return e.category === "replan" || e.category === "sim" || e.category === "recovery"; });
    // replan labels get a band of their own between the time axis and the rows, so they
    // never sit on a robot's bars
    var band = markers.some(function (e) { return e.category === "replan"; }) ? 14 : 0;
    var rowH = 32, top = 24 + band, left = 84, right = 14, bottom = 6;
    var state = { svg: null, cursor: null, head: null, x: null, bars: [], active: {}, dragging: false, seek: null };

    function render() {
      box.textContent = "";
      var width = Math.max(320, box.clientWidth || 800);
      var height = top + robots.length * rowH + bottom;
      var plotW = width - left - right;
      function x(t) { return left + (t / END) * plotW; }
      state.x = x;
      var root = svg("svg", { viewBox: "0 0 " + width + " " + height, width: width, height: height,
                              role: "img", "aria-label": "Gantt chart of the robots' actions" }, box);
      state.svg = root;
      var defs = svg("defs", {}, root);
      var pat = svg("pattern", { id: "hatch", width: 6, height: 6, patternUnits: "userSpaceOnUse", patternTransform: "rotate(45)" }, defs);
      svg("rect", { width: 6, height: 6, fill: "rgba(255,255,255,0)" }, pat);
      svg("line", { x1: 0, y1: 0, x2: 0, y2: 6, stroke: "rgba(255,255,255,.75)", "stroke-width": 2.4 }, pat);
      var mk = svg("marker", { id: "arrow", viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" }, defs);
      svg("path", { d: "M0,0 L10,5 L0,10 z", fill: "#39424c" }, mk);
      var mk2 = svg("marker", { id: "arrow-bad", viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" }, defs);
      svg("path", { d: "M0,0 L10,5 L0,10 z", fill: "#d64541" }, mk2);

      var axis = svg("g", { class: "axis" }, root);
      var step = ET.niceStep(END, Math.max(3, Math.floor(plotW / 80)));
      for (var tt = 0; tt <= END + 1e-9; tt += step) {
        svg("line", { x1: x(tt), x2: x(tt), y1: top - 4, y2: height - bottom }, axis);
        svg("text", { x: x(tt), y: 15 }, axis, (step < 1 ? tt.toFixed(1) : Math.round(tt)) + " s");
      }
      var rows = svg("g", {}, root);
      robots.forEach(function (r, i) {
        var y = top + i * rowH;
        var row = svg("g", { class: "gantt-row", "data-robot": r }, rows);
        if (i % 2 === 0) svg("rect", { class: "row-bg", x: 0, y: y, width: width, height: rowH }, row);
        svg("rect", { x: 6, y: y + rowH / 2 - 6, width: 12, height: 12, rx: 3, fill: robotColor(r) }, row);
        svg("text", { class: "row-label", x: 24, y: y + rowH / 2 }, row, r);
      });
      var barLayer = svg("g", {}, root);
      var rowOf = {};
      robots.forEach(function (r, i) { rowOf[r] = i; });
      state.bars = [];
      var labels = [];  // every text drawn on the plot, in priority order (see declutter)
      TL.actions.forEach(function (a, idx) {
        var y = top + rowOf[a.robot] * rowH + 5;
        var x0 = x(a.start), w = Math.max(1.5, x(a.end) - x0);
        var fill = barColor(a);
        var rect = svg("rect", { class: "bar" + (a.recovery ? " recovery" : ""), x: x0, y: y, width: w, height: rowH - 10,
                                 rx: 3, fill: fill, "data-index": idx }, barLayer);
        state.bars.push(rect);
        if (a.recovery) svg("rect", { x: x0, y: y, width: w, height: rowH - 10, rx: 3, fill: "url(#hatch)", "pointer-events": "none" }, barLayer);
        var label = shortSkill(a.skill) + (a.args.length ? " " + a.args[0] : "");
        var text = svg("text", { class: "bar-label" + (a.outcome === "unfinished" || a.reason === "spot_busy" ? " dark" : ""),
                                 x: x0 + 4, y: y + (rowH - 10) / 2 }, barLayer, label);
        if (fitLabel(text, [label, shortSkill(a.skill)], w - 7)) labels.push(text);
      });
      var syncLayer = svg("g", {}, root);
      edges.forEach(function (e) {
        // from the producer's end (bottom or top edge of its bar) to the consumer's start
        var r1 = rowOf[e.from.robot], r2 = rowOf[e.to.robot];
        var down = r2 > r1;
        var sx = x(e.from.end), sy = top + r1 * rowH + (down ? rowH - 5 : 5);
        var ex = x(e.to.start), ey = top + r2 * rowH + (down ? 5 : rowH - 5);
        var my = (sy + ey) / 2;
        var violated = e.to.start + 1e-6 < e.from.end;
        var p = svg("path", { class: "sync" + (violated ? " violated" : ""),
                              d: "M" + sx + "," + sy + " C" + sx + "," + my + " " + ex + "," + my + " " + ex + "," + ey,
                              "marker-end": violated ? "url(#arrow-bad)" : "url(#arrow)" }, syncLayer);
        svg("title", {}, p, e.consumer + " waits for " + e.producer + (e.reason ? ": " + e.reason : "") + (violated ? " (started before it ended!)" : ""));
      });
      var markLayer = svg("g", {}, root);
      markers.forEach(function (ev) {
        if (ev.category === "replan") {
          var g = svg("g", { class: "replan" }, markLayer);
          svg("line", { x1: x(ev.t), x2: x(ev.t), y1: top, y2: height - bottom }, g);
          // name what caused the replan: a breakdown, a joiner, a lost object, the plan ending
          var rtext = svg("text", { x: x(ev.t) + 3, y: top - 4 }, g, "replan" + replanCause(ev.key));
          fitLabel(rtext, [rtext.textContent, "replan"], width - right - x(ev.t) - 3);
          labels.push(rtext);
          svg("title", {}, g, "replan at " + ev.t.toFixed(2) + " s: " + ev.key + " " + ev.value);
        } else if (ev.category === "recovery" && ev.robot in rowOf) {
          var ry = top + rowOf[ev.robot] * rowH + rowH - 3, rx = x(ev.t);
          var dia = svg("path", { class: "recmark", d: "M" + rx + "," + (ry - 4) + " l4,4 l-4,4 l-4,-4 z" }, markLayer);
          svg("title", {}, dia, "recovery at " + ev.t.toFixed(2) + " s (" + ev.key + "): " + ev.value);
        } else if (ev.key === "breakdown" || ev.key === "join" || ev.key === "drop" || ev.key === "moved") {
          var ri = ev.robot in rowOf ? rowOf[ev.robot] : (ev.value in rowOf ? rowOf[ev.value] : -1);
          var cy = ri >= 0 ? top + ri * rowH + 4 : top + 2;
          var tri = svg("path", { class: "simmark", d: "M" + (x(ev.t) - 5) + "," + (cy - 4) + " L" + (x(ev.t) + 5) + "," + (cy - 4) + " L" + x(ev.t) + "," + (cy + 5) + " z" }, markLayer);
          svg("title", {}, tri, ev.key + " at " + ev.t.toFixed(2) + " s: " + ev.value);
          // the disturbances a benchmark injects are labelled on the chart, not only in the tooltip
          var label = ev.key === "breakdown" ? "✕ " + ev.value + " down" : ev.key === "join" ? "+ " + ev.value + " joins"
            : ev.key === "moved" ? "moved " + ev.value.split(" ")[0] : null;
          if (label) labels.push(svg("text", { class: "simlabel", x: x(ev.t) + 7, y: cy + 4 }, markLayer, label));
        }
      });
      declutter(labels);
      state.cursor = svg("line", { class: "cursor", x1: x(clock.t), x2: x(clock.t), y1: top - 4, y2: height - bottom }, root);
      state.head = svg("path", { class: "cursor-head", d: "M-5,0 L5,0 L0,6 z", transform: "translate(" + x(clock.t) + "," + (top - 4) + ")" }, root);
      state.active = {};

      barLayer.addEventListener("mousemove", function (ev) {
        var i = ev.target.getAttribute("data-index");
        if (i === null) return;
        var a = TL.actions[Number(i)];
        var lines = [a.action, a.robot + (a.step ? " · step " + a.step : "") + (a.recovery ? " · recovery" : ""),
                     a.start.toFixed(2) + " – " + a.end.toFixed(2) + " s (" + (a.end - a.start).toFixed(2) + " s)"];
        lines.push(a.outcome === "failed" ? "failed: " + (a.reason || "?") + (a.message ? " — " + a.message : "") : a.outcome);
        ET.showTip(lines, ev.clientX, ev.clientY);
        mapFocus(a.args);
      });
      barLayer.addEventListener("mouseleave", function () { ET.hideTip(); mapFocus([]); });
      state.seek = function (ev) {
        var rect = root.getBoundingClientRect();
        var px = (ev.clientX - rect.left) * (width / rect.width);
        setTime(((px - left) / plotW) * END);
      };
      root.addEventListener("pointerdown", function (ev) { state.dragging = true; state.seek(ev); });
      update(clock.t);
    }

    function update(t) {
      if (!state.cursor) return;
      var xx = state.x(t);
      state.cursor.setAttribute("x1", xx);
      state.cursor.setAttribute("x2", xx);
      state.head.setAttribute("transform", "translate(" + xx + "," + (top - 4) + ")");
      robots.forEach(function (r) {
        var list = actionsByRobot[r];
        var i = lastLE(list.starts, t);
        var idx = i >= 0 && t <= list.bars[i].end ? list.idx[i] : -1;
        if (state.active[r] === idx) return;
        if (state.active[r] !== undefined && state.active[r] >= 0) state.bars[state.active[r]].classList.remove("active");
        if (idx >= 0) state.bars[idx].classList.add("active");
        state.active[r] = idx;
      });
    }
    // dragging over the chart scrubs; registered once, not per render
    window.addEventListener("pointermove", function (ev) { if (state.dragging) state.seek(ev); });
    window.addEventListener("pointerup", function () { state.dragging = false; });
    render();
    listeners.push(update);
    var pending = null;
    window.addEventListener("resize", function () {
      clearTimeout(pending);
      pending = setTimeout(render, 120);
    });

    var legend = document.getElementById("gantt-legend");
    function item(color, text, cls) {
      var it = el("span", { class: "item" }, legend);
      el("span", { class: "swatch " + (cls || ""), style: "background:" + color }, it);
      el("span", {}, it, text);
    }
    var seen = {};
    TL.actions.forEach(function (a) { seen[outcomeKey(a)] = a; });
    if (seen.success || !TL.actions.length) item(OUTCOME_COLORS.success, "success");
    Object.keys(seen).sort().forEach(function (k) {
      if (k.indexOf("failed:") === 0) item(barColor(seen[k]), "failed: " + k.slice(7).replace(/_/g, " "));
    });
    if (seen.unfinished) item(OUTCOME_COLORS.unfinished, "unfinished");
    var rec = el("span", { class: "item" }, legend);
    el("span", { class: "swatch", style: "background: repeating-linear-gradient(45deg,#3a9b5c 0 3px,#c5e3cf 3px 5px); border: 1px dashed #222" }, rec);
    el("span", {}, rec, "recovery action");
    var ar = el("span", { class: "item" }, legend);
    el("span", { class: "mono" }, ar, "⟶");
    el("span", {}, ar, "sync dependency (" + edges.length + ")");
    if (markers.some(function (e) { return e.category === "recovery"; })) {
      var rc = el("span", { class: "item" }, legend);
      el("span", { style: "color:#b8860b;font-size:13px" }, rc, "◆");
      el("span", {}, rc, "recovery started");
    }
    if (markers.some(function (e) { return e.category === "replan"; })) item("#7b3294", "replan", "");
    if (markers.some(function (e) { return e.key === "breakdown" || e.key === "join" || e.key === "moved"; })) {
      var dm = el("span", { class: "item" }, legend);
      el("span", { style: "color:#555;font-size:12px" }, dm, "▼");
      el("span", {}, dm, "disturbance (breakdown, joiner, moved object)");
    }
  }

  /* ---------------- behavior tree ---------------- */
  function buildTree() {
    var box = document.getElementById("tree");
    var T = D.tree;
    var caption = document.getElementById("tree-caption");
    caption.textContent = T.source === "trace" ? "from the executor's node events · " + T.nodes.length + " nodes"
      : T.source === "plan" ? "shape from the plan, statuses derived from actions (no node events in the trace)"
      : "";
    var legend = document.getElementById("tree-legend");
    [["var(--run)", "running"], ["var(--ok)", "success"], ["var(--bad)", "failure"], ["var(--idle)", "not ticked"]].forEach(function (s) {
      var it = el("span", { class: "item" }, legend);
      el("span", { class: "swatch round", style: "background:" + s[0] }, it);
      el("span", {}, it, s[1]);
    });
    if (!T.nodes.length) {
      // full, no-hp and no-pfg-hp execute behavior trees; the other modes run action lists
      var treeMode = ["full", "no-hp", "no-pfg-hp"].indexOf(D.meta.mode) >= 0;
      el("div", { class: "empty" }, box, treeMode
        ? "No behavior tree: the episode ended before its tree was built (see the outcome above)."
        : "No behavior tree: mode " + D.meta.mode + " executes action lists, not a tree.");
      document.getElementById("tree-expand").hidden = true;
      document.getElementById("tree-collapse").hidden = true;
      return;
    }
    var rootUl = el("ul", {}, box);
    var lists = {};
    var items = [];
    T.nodes.forEach(function (n) {
      var parentUl = n.parent === null ? rootUl : lists[n.parent];
      if (!parentUl) {
        var li0 = items[n.parent].li;
        parentUl = lists[n.parent] = el("ul", {}, li0);
        items[n.parent].caret.textContent = "▾";
      }
      var li = el("li", { "data-node": n.id }, parentUl);
      var row = el("div", { class: "node st-idle", title: n.name + (n.note ? "\n" + n.note : "") }, li);
      var caret = el("span", { class: "caret" }, row, "");
      el("span", { class: "dot" }, row);
      if (n.depth > 0 && n.kind === "robot") el("span", { class: "robot-swatch", style: "background:" + robotColor(n.name) }, row);
      if (n.kind !== "node") el("span", { class: "kind" }, row, n.kind);
      el("span", { class: "name" }, row, n.name);
      if (n.note) el("span", { class: "note" }, row, "· " + n.note);
      var times = n.changes.map(function (c) { return c[0]; });
      var statuses = n.changes.map(function (c) { return c[1]; });
      items[n.id] = { li: li, row: row, caret: caret, times: times, statuses: statuses, st: "idle", node: n };
      row.addEventListener("dblclick", function () { if (times.length) setTime(times[0]); });
    });
    // only nodes whose ancestors are all expanded are updated per frame: a collapsed step
    // hides its five children, and a long episode has thousands of them
    var shown = [];
    var lastT = null;
    function refreshShown() {
      shown = [];
      var open = {};
      items.forEach(function (it) {
        var p = it.node.parent;
        var vis = p === null || (open[p] && !items[p].li.classList.contains("collapsed"));
        open[it.node.id] = vis;
        if (vis) shown.push(it);
      });
      if (lastT !== null) paint(lastT);
    }
    function paint(t) {
      lastT = t;
      for (var i = 0; i < shown.length; i++) {
        var it = shown[i];
        var j = lastLE(it.times, t);
        var st = j < 0 ? "idle" : it.statuses[j];
        if (st === it.st) continue;
        it.row.classList.remove("st-" + it.st);
        it.row.classList.add("st-" + st);
        it.row.setAttribute("data-status", st);
        it.st = st;
      }
    }
    items.forEach(function (it) {
      it.caret.addEventListener("click", function () {
        it.li.classList.toggle("collapsed");
        it.caret.textContent = it.li.classList.contains("collapsed") ? "▸" : "▾";
        refreshShown();
      });
    });
    // collapsed by default: each step (the whole subtree of one plan step), or below
    // depth 2 when the names do not say which nodes are steps
    var hasSteps = T.nodes.some(function (n) { return n.kind === "step"; });
    function collapseSteps() {
      items.forEach(function (it) {
        var collapse = lists[it.node.id] && (hasSteps ? it.node.kind === "step" : it.node.depth >= 2);
        it.li.classList.toggle("collapsed", !!collapse);
        if (lists[it.node.id]) it.caret.textContent = collapse ? "▸" : "▾";
      });
      refreshShown();
    }
    collapseSteps();
    document.getElementById("tree-collapse").addEventListener("click", collapseSteps);
    document.getElementById("tree-expand").addEventListener("click", function () {
      items.forEach(function (it) { it.li.classList.remove("collapsed"); if (lists[it.node.id]) it.caret.textContent = "▾"; });
      refreshShown();
    });
    listeners.push(paint);
  }

  /* ---------------- blackboard & events ---------------- */
  function buildEvents() {
    var events = TL.events;
    var caption = document.getElementById("events-caption");
    caption.textContent = events.length + " events";
    var filters = document.getElementById("event-filters");
    var counts = {};
    events.forEach(function (e) { counts[e.category] = (counts[e.category] || 0) + 1; });
    var cats = CATEGORIES.filter(function (c) { return counts[c]; });
    var on = {};
    cats.forEach(function (c) {
      on[c] = true;
      var chip = el("button", { type: "button", class: "chip", "data-category": c, "aria-pressed": "true" }, filters);
      el("span", { class: "swatch round", style: "background:" + CATEGORY_COLORS[c] }, chip);
      el("span", {}, chip, CATEGORY_LABELS[c] + " " + counts[c]);
      chip.addEventListener("click", function () {
        on[c] = !on[c];
        chip.classList.toggle("off", !on[c]);
        chip.setAttribute("aria-pressed", String(on[c]));
        applyFilter();
      });
    });
    var robotSel = el("select", { "aria-label": "Filter by robot" }, filters);
    el("option", { value: "" }, robotSel, "all robots");
    TL.robots.forEach(function (r) { el("option", { value: r }, robotSel, r); });
    var search = el("input", { type: "search", placeholder: "filter key or value", "aria-label": "Filter text" }, filters);
    var followLabel = el("label", { class: "muted" }, filters);
    var followBox = el("input", { type: "checkbox", checked: true }, followLabel);
    followLabel.appendChild(document.createTextNode(" follow time"));

    // timeline strip: one lane per category, one tick per event (a single path per lane)
    var strip = document.getElementById("event-strip");
    var laneH = 13, left = 92, right = 8;
    var stripState = {};
    function drawStrip() {
      strip.textContent = "";
      if (!cats.length) return;
      var width = Math.max(260, strip.clientWidth || 400);
      var plotW = width - left - right;
      var height = cats.length * laneH + 4;
      var root = svg("svg", { viewBox: "0 0 " + width + " " + height, width: width, height: height }, strip);
      cats.forEach(function (c, i) {
        var y = 2 + i * laneH;
        svg("rect", { class: "lane-bg", x: left, y: y + 1, width: plotW, height: laneH - 2 }, root);
        svg("text", { class: "lane-label", x: 0, y: y + laneH / 2 }, root, CATEGORY_LABELS[c]);
        var d = [];
        events.forEach(function (e) {
          if (e.category === c && visible(e)) d.push("M" + (left + (e.t / END) * plotW).toFixed(1) + "," + (y + 2) + "v" + (laneH - 4));
        });
        if (d.length) svg("path", { d: d.join(""), stroke: CATEGORY_COLORS[c], "stroke-width": 1.6 }, root);
      });
      stripState.cursor = svg("line", { class: "cursor", y1: 0, y2: height }, root);
      stripState.x = function (t) { return left + (t / END) * plotW; };
      root.addEventListener("pointerdown", function (ev) {
        var rect = root.getBoundingClientRect();
        setTime((((ev.clientX - rect.left) * (width / rect.width)) - left) / plotW * END);
      });
      moveStrip(clock.t);
    }
    function moveStrip(t) {
      if (!stripState.cursor) return;
      var x = stripState.x(t);
      stripState.cursor.setAttribute("x1", x);
      stripState.cursor.setAttribute("x2", x);
    }

    // The list is virtual: only the rows in view exist in the DOM (a long episode logs
    // thousands of events, and re-styling thousands of rows per frame is what makes a
    // page stutter). Rows have a fixed height; a spacer gives the scrollbar its length.
    var ROW_H = 32;  // two lines: a long key wraps (episode.css)
    var list = document.getElementById("event-list");
    var times = events.map(function (e) { return e.t; });
    var filtered = events.map(function (_, i) { return i; });
    var current = -1;  // index into `filtered` of the last shown event at or before t
    var head = el("div", { class: "ev-row ev-head" }, list);
    ["t (s)", "", "robot", "key", "value"].forEach(function (h) { el("span", {}, head, h); });
    var spacer = el("div", { class: "ev-spacer" }, list);
    var windowBox = el("div", { class: "ev-window" }, spacer);
    var empty = el("div", { class: "empty" }, list, events.length ? "No event matches the filter."
                                                                  : "No blackboard, simulator or replanning events in this trace.");
    var pool = [];
    function rowAt(k) {
      if (pool[k]) return pool[k];
      var r = el("div", { class: "ev-row" }, windowBox);
      var cells = [el("span", { class: "mono num" }, r), el("span", {}, r), el("span", {}, r),
                   el("span", { class: "mono" }, r), el("span", { class: "mono val" }, r)];
      var badge = el("span", { class: "cat" }, cells[1]);
      pool[k] = { row: r, cells: cells, badge: badge, i: -1 };
      return pool[k];
    }
    function renderRows() {
      spacer.style.height = filtered.length * ROW_H + "px";
      empty.hidden = filtered.length > 0;
      // the scroll position may be stale (the filter just shortened the list): clamp it
      var inView = Math.ceil((list.clientHeight || 300) / ROW_H);
      var first = Math.floor((list.scrollTop - head.offsetHeight) / ROW_H) - 4;
      first = Math.max(0, Math.min(first, filtered.length - inView));
      var count = Math.max(0, Math.min(filtered.length - first, inView + 10));
      windowBox.style.transform = "translateY(" + first * ROW_H + "px)";
      for (var k = 0; k < Math.max(count, pool.length); k++) {
        var slot = k < count ? rowAt(k) : pool[k];
        if (k >= count) { slot.row.hidden = true; slot.i = -1; continue; }
        slot.row.hidden = false;
        var fi = first + k, i = filtered[fi];
        if (slot.i !== i) {
          var e = events[i];
          slot.i = i;
          slot.row.setAttribute("data-i", i);
          slot.cells[0].textContent = e.t.toFixed(2);
          slot.badge.textContent = CATEGORY_BADGES[e.category];
          slot.badge.style.background = CATEGORY_COLORS[e.category];
          slot.cells[2].textContent = e.robot || "";
          slot.cells[2].style.color = e.robot ? robotColor(e.robot) : "";
          slot.cells[3].textContent = e.key;
          slot.cells[4].textContent = e.value;
          slot.row.title = e.key + " = " + e.value;
        }
        slot.row.classList.toggle("future", fi > current);
        slot.row.classList.toggle("current", fi === current);
      }
    }
    list.addEventListener("scroll", renderRows);
    windowBox.addEventListener("click", function (ev) {
      var r = ev.target.closest(".ev-row");
      if (r && r.hasAttribute("data-i")) setTime(events[Number(r.getAttribute("data-i"))].t);
    });

    function visible(e) {
      if (!on[e.category]) return false;
      if (robotSel.value && e.robot !== robotSel.value) return false;
      var q = search.value.trim().toLowerCase();
      return !q || e.key.toLowerCase().indexOf(q) >= 0 || e.value.toLowerCase().indexOf(q) >= 0;
    }
    function locate(t) {
      // last filtered event at or before t: binary search over the filtered indices
      var lo = 0, hi = filtered.length - 1, ans = -1;
      while (lo <= hi) {
        var mid = (lo + hi) >> 1;
        if (times[filtered[mid]] <= t) { ans = mid; lo = mid + 1; } else { hi = mid - 1; }
      }
      return ans;
    }
    function keepCurrentInView() {
      if (!followBox.checked || current < 0) return;
      var y = head.offsetHeight + current * ROW_H;
      var h = list.clientHeight || 300;
      if (y < list.scrollTop + ROW_H || y > list.scrollTop + h - 2 * ROW_H) list.scrollTop = Math.max(0, y - h / 2);
    }
    function applyFilter() {
      filtered = [];
      events.forEach(function (e, i) { if (visible(e)) filtered.push(i); });
      current = locate(clock.t);
      drawStrip();
      renderRows();
      keepCurrentInView();
    }
    robotSel.addEventListener("change", applyFilter);
    search.addEventListener("input", applyFilter);
    caption.textContent = events.length + " events";

    listeners.push(function (t) {
      moveStrip(t);
      var cur = locate(t);
      if (cur === current) return;
      current = cur;
      var before = list.scrollTop;
      keepCurrentInView();
      if (list.scrollTop === before) renderRows();  // a scroll re-renders by itself
    });
    renderRows();
    drawStrip();
    var pending = null;
    window.addEventListener("resize", function () { clearTimeout(pending); pending = setTimeout(drawStrip, 120); });
  }

  /* ---------------- details ---------------- */
  function buildDetails() {
    var box = document.getElementById("conditions");
    if (!D.conditions.length) {
      el("div", { class: "empty" }, box, "No goal conditions were checked (the episode ended early).");
    } else {
      var t = el("table", { class: "data" }, box);
      var h = el("tr", {}, el("thead", {}, t));
      ["", "condition", "satisfied"].forEach(function (x, i) { el("th", { class: i === 2 ? "num" : null }, h, x); });
      var b = el("tbody", {}, t);
      D.conditions.forEach(function (c) {
        var tr = el("tr", {}, b);
        el("td", { class: c.holds ? "yes" : "no" }, tr, c.holds ? "✓" : "✗");
        el("td", { class: "mono" }, tr, c.condition);
        el("td", { class: "num" }, tr, c.satisfied + " / " + c.required);
      });
    }
    var facts = el("dl", { class: "facts" }, document.getElementById("run-facts"));
    function fact(k, v) { el("dt", {}, facts, k); el("dd", {}, facts, v); }
    var m = D.meta, k = D.metrics, f = m.faults;
    fact("task", m.task);
    fact("floor plan", m.floor_plan + (m.room ? " · " + m.room.replace("_", " ") : ""));
    fact("mode / front end", m.mode + " / " + m.frontend);
    fact("seed", String(m.seed));
    var faults = [];
    if (f.action_failure) faults.push("action failure p=" + f.action_failure);
    if (f.occlusion) faults.push("occlusion p=" + f.occlusion);
    (f.breakdowns || []).forEach(function (b) { faults.push(b.robot + " breaks down at " + b.at + " s"); });
    (f.moves || []).forEach(function (mv) { faults.push(mv.object + " moved at " + mv.at + " s"); });
    fact("faults", faults.length ? faults.join("; ") : "none");
    fact("wall time", ET.secs(k.wall_seconds));
    if (D.plan) fact("planner", D.plan.planner_calls + " Fast Downward call" + (D.plan.planner_calls === 1 ? "" : "s") +
                     (D.plan.joint ? " (joint problem)" : "") + ", " + ET.secs(D.plan.plan_seconds));

    var ts = document.getElementById("taskspec");
    if (!D.taskspec) {
      el("div", { class: "empty" }, ts, "No TaskSpec (mode " + m.mode + ", or the front end failed).");
    } else {
      var tt = el("table", { class: "data" }, ts);
      var hh = el("tr", {}, el("thead", {}, tt));
      ["id", "subtask", "robot", "goal", "after"].forEach(function (x) { el("th", {}, hh, x); });
      var bb = el("tbody", {}, tt);
      D.taskspec.subtasks.forEach(function (s) {
        var tr = el("tr", {}, bb);
        el("td", { class: "mono" }, tr, s.id);
        el("td", {}, tr, s.description + (s.final ? "" : " (intermediate)"));
        var rc = el("td", {}, tr);
        if (s.robot) el("span", { style: "color:" + robotColor(s.robot) + ";font-weight:600" }, rc, s.robot);
        else rc.textContent = "any";
        el("td", { class: "mono" }, tr, (D.taskspec_text[s.id] || []).join(", "));
        el("td", { class: "mono" }, tr, s.depends_on.join(", "));
      });
    }

    var pl = document.getElementById("plan");
    if (!D.plan) {
      el("div", { class: "empty" }, pl, "No merged plan (mode " + m.mode + ", or planning failed).");
      return;
    }
    var P = D.plan;
    var nSteps = 0;
    Object.keys(P.robots).forEach(function (r) { nSteps += P.robots[r].length; });
    document.getElementById("plan-caption").textContent = nSteps + " steps · " + P.sync.length + " sync points" +
      (P.makespan ? " · planned makespan " + ET.secs(P.makespan) : "");
    var firstStart = {};
    TL.actions.forEach(function (a) { if (a.step && !(a.step in firstStart)) firstStart[a.step] = a.start; });
    var grid = el("div", { class: "plan-robots" }, pl);
    Object.keys(P.robots).forEach(function (r) {
      var col = el("div", { class: "plan-robot" }, grid);
      var h3 = el("h3", {}, col);
      el("span", { class: "swatch", style: "background:" + robotColor(r) }, h3);
      el("span", {}, h3, r);
      var ol = el("ol", {}, col);
      P.robots[r].forEach(function (s) {
        var li = el("li", { title: "subtask " + s.subtask + (s.resources.length ? " · holds " + s.resources.join(", ") : "") +
                                 (s.pre.length ? "\npre: " + s.pre.join(" ") : "") + (s.post.length ? "\npost: " + s.post.join(" ") : "") }, ol);
        el("span", { class: "mono" }, li, s.action);
        s.waits.forEach(function (w) { el("span", { class: "wait", title: w.reason || null }, li, "⟵ " + w.step); });
        li.addEventListener("click", function () { if (s.id in firstStart) setTime(firstStart[s.id]); });
      });
    });
  }

  /* ---------------- playback ---------------- */
  function buildControls() {
    var play = document.getElementById("play");
    var speed = document.getElementById("speed");
    var scrub = document.getElementById("scrubber");
    var clockText = document.getElementById("clock");
    scrub.max = String(END);
    scrub.step = String(Math.max(0.01, END / 4000));
    var speeds = [0.25, 0.5, 1, 2, 5, 10, 20, 50, 100];
    var preferred = speeds.filter(function (s) { return END / s <= 30; })[0] || 100;
    speeds.forEach(function (s) { el("option", { value: s, selected: s === preferred }, speed, s + "×"); });
    var playing = false, last = null;
    function frame(ts) {
      if (!playing) return;
      if (last !== null) {
        var t = clock.t + ((ts - last) / 1000) * Number(speed.value);
        if (t >= END) { setTime(END); stop(); return; }
        setTime(t);
      }
      last = ts;
      requestAnimationFrame(frame);
    }
    function start() {
      if (clock.t >= END) setTime(0);
      playing = true; last = null;
      play.innerHTML = "&#10074;&#10074;";
      play.setAttribute("aria-label", "Pause");
      requestAnimationFrame(frame);
    }
    function stop() {
      playing = false;
      play.innerHTML = "&#9654;";
      play.setAttribute("aria-label", "Play");
    }
    play.addEventListener("click", function () { if (playing) stop(); else start(); });
    scrub.addEventListener("input", function () { setTime(Number(scrub.value)); });
    document.addEventListener("keydown", function (ev) {
      var tag = (ev.target.tagName || "").toLowerCase();
      // typing in a field, or space on a focused button (its own click handles it)
      if ((tag === "input" && ev.target.type !== "range") || tag === "select" || tag === "textarea" || tag === "button") return;
      if (ev.key === " ") { ev.preventDefault(); if (playing) stop(); else start(); }
      else if (tag !== "input" && ev.key === "ArrowRight") setTime(clock.t + END / 100);
      else if (tag !== "input" && ev.key === "ArrowLeft") setTime(clock.t - END / 100);
    });
    listeners.push(function (t) {
      if (Number(scrub.value) !== t) scrub.value = String(t);
      clockText.textContent = "t = " + t.toFixed(2) + " / " + END.toFixed(2) + " s";
    });
  }

  buildHeader();
  buildControls();
  buildMap();
  buildGantt();
  buildTree();
  buildEvents();
  buildDetails();
  document.getElementById("footer").textContent = "Generated by " + D.generator + " · " + TL.actions.length + " actions · " +
    TL.robots.length + " robots · self-contained page (no network)";
  var m = /[#&]t=([0-9.]+)/.exec(window.location.hash);
  setTime(m ? Number(m[1]) : 0);
  window.emboteamReport = { setTime: setTime, time: function () { return clock.t; }, end: END };
})();
