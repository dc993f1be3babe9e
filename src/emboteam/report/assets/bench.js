/* EmboTeam benchmark index: summary, plots and a sortable, filterable table of episodes,
   each linking to its episode viewer. Data from #bench-data (emboteam.report.bench_index). */
(function () {
  "use strict";
  var el = ET.el;
  var D = ET.data("bench-data");
  var S = D.summary || {};

  var RATES = { sr: 1, gcr: 1, exec: 1 };
  var LABELS = { n: "episodes", sr: "SR", sr_ci: "SR 95% CI", gcr: "GCR", exec: "Exec", makespan_mean: "makespan (mean)",
                 plan_seconds_p50: "plan time (p50)", llm_calls_mean: "LLM calls (mean)",
                 tokens_mean: "tokens (mean)", errors: "errors" };

  function fmt(key, v) {
    if (v === null || v === undefined) return "–";
    if (Array.isArray(v) && v.length === 2 && typeof v[0] === "number" && /_ci$/.test(key)) {
      var base = key.replace(/_ci$/, "");
      return fmt(base, v[0]) + " – " + fmt(base, v[1]);  // a confidence interval
    }
    if (typeof v === "boolean") return v ? "yes" : "no";
    if (typeof v !== "number") return String(v);
    if (RATES[key]) return ET.pct(v);
    if (/seconds|makespan/.test(key)) return ET.secs(v);
    if (Number.isInteger(v)) return v.toLocaleString("en-US");
    return v.toFixed(2);
  }

  function buildSummary() {
    document.getElementById("suite-title").textContent = (S.suite || "benchmark") + " · EmboTeam benchmark";
    document.getElementById("suite-line").textContent = D.rows.length + " episodes · open a row's report to replay it";
    var cards = document.getElementById("summary-metrics");
    Object.keys(LABELS).forEach(function (k) {
      if (!(k in S) || (S[k] && typeof S[k] === "object" && !Array.isArray(S[k]))) return;
      var c = el("div", { class: "metric" }, cards);
      el("div", { class: "label" }, c, LABELS[k]);
      el("div", { class: "value" }, c, fmt(k, S[k]));
    });
    var box = document.getElementById("summary");
    var other = Object.keys(S).filter(function (k) { return !(k in LABELS) && k !== "suite"; });
    other.forEach(function (k) {
      var v = S[k];
      if (v && typeof v === "object" && !Array.isArray(v) && Object.keys(v).every(function (r) { return v[r] && typeof v[r] === "object"; })) {
        el("h2", { class: "spaced" }, box, k.replace(/_/g, " "));
        var cols = [];
        Object.keys(v).forEach(function (r) { Object.keys(v[r]).forEach(function (c) { if (cols.indexOf(c) < 0) cols.push(c); }); });
        var t = el("table", { class: "data" }, box);
        var h = el("tr", {}, el("thead", {}, t));
        el("th", {}, h, "");
        cols.forEach(function (c) { el("th", { class: "num" }, h, LABELS[c] || c); });
        var b = el("tbody", {}, t);
        Object.keys(v).forEach(function (r) {
          var tr = el("tr", {}, b);
          el("td", {}, tr, r);
          cols.forEach(function (c) { el("td", { class: "num" }, tr, fmt(c, v[r][c])); });
        });
      } else {
        var p = el("p", {}, box);
        el("span", { class: "muted" }, p, k.replace(/_/g, " ") + ": ");
        el("span", { class: "mono" }, p, typeof v === "object" ? JSON.stringify(v) : fmt(k, v));
      }
    });
    if (!box.childNodes.length) el("div", { class: "empty" }, box, "The headline numbers are above; no per-category breakdown.");
    var tables = document.getElementById("tables-panel");
    if (!tables.children.length) tables.hidden = true;
  }

  function buildPlots() {
    var box = document.getElementById("plots");
    if (!D.plots.length) { document.getElementById("plots-panel").hidden = true; return; }
    D.plots.forEach(function (p) {
      var f = el("figure", {}, box);
      el("img", { src: p.src, alt: p.title }, f);
      el("figcaption", {}, f, p.title + " (" + p.file + ")");
    });
  }

  var COLUMNS = [
    { key: "task", label: "task" }, { key: "category", label: "category" }, { key: "mode", label: "mode" },
    { key: "frontend", label: "front end" }, { key: "seed", label: "seed", num: true },
    { key: "faults", label: "faults", num: true }, { key: "success", label: "success" },
    { key: "gcr", label: "GCR", num: true }, { key: "exec", label: "Exec", num: true },
    { key: "makespan", label: "makespan", num: true }, { key: "actions", label: "actions", num: true },
    { key: "llm_calls", label: "LLM calls", num: true }, { key: "tokens", label: "tokens", num: true },
    { key: "error", label: "error" }, { key: "link", label: "report" }
  ];

  function buildEpisodes() {
    var rows = D.rows;
    var table = document.getElementById("episodes");
    var head = el("tr", {}, el("thead", {}, table));
    var body = el("tbody", {}, table);
    var sortKey = null, sortDir = 1;
    var ths = COLUMNS.map(function (c) {
      var th = el("th", { class: c.num ? "num" : null, "data-key": c.key, scope: "col" }, head, c.label);
      if (c.key !== "link") th.addEventListener("click", function () { sortBy(c.key); });
      return th;
    });

    // one <tr> per episode, built once; filtering hides rows, sorting reorders them
    var trs = rows.map(function (r, i) {
      var tr = el("tr", { "data-i": i });
      COLUMNS.forEach(function (c) {
        var v = r[c.key];
        if (c.key === "link") {
          var td = el("td", {}, tr);
          if (v) el("a", { href: v }, td, "open");
          else el("span", { class: "muted" }, td, "none");
        } else if (c.key === "success") {
          el("td", { class: v ? "yes" : "no" }, tr, v ? "✓" : "✗");
        } else if (c.key === "error") {
          el("td", { class: "err" }, tr, v);
        } else if (c.key === "task") {
          el("td", { class: "mono" }, tr, v);
        } else {
          el("td", { class: c.num ? "num" : null }, tr, fmt(c.key, v));
        }
      });
      body.appendChild(tr);
      return tr;
    });

    var filters = document.getElementById("episode-filters");
    var search = el("input", { type: "search", placeholder: "filter task, error…", "aria-label": "Filter episodes" }, filters);
    var selects = {};
    ["mode", "frontend", "category", "faults"].forEach(function (k) {
      var values = [];
      rows.forEach(function (r) { if (values.indexOf(r[k]) < 0) values.push(r[k]); });
      if (values.length < 2) return;
      var lab = el("label", {}, filters, k === "frontend" ? "front end" : k);
      var sel = el("select", { "data-filter": k }, lab);
      el("option", { value: "" }, sel, "all");
      values.sort().forEach(function (v) { el("option", { value: String(v) }, sel, String(v)); });
      sel.addEventListener("change", apply);
      selects[k] = sel;
    });
    var outcome = el("select", { "data-filter": "outcome", "aria-label": "Outcome" }, el("label", {}, filters, "outcome"));
    [["", "all"], ["success", "success"], ["failed", "failed"], ["error", "with error"]].forEach(function (o) {
      el("option", { value: o[0] }, outcome, o[1]);
    });
    outcome.addEventListener("change", apply);
    search.addEventListener("input", apply);
    var count = document.getElementById("episodes-count");

    function apply() {
      var q = search.value.trim().toLowerCase();
      var shown = 0;
      rows.forEach(function (r, i) {
        var ok = !q || (r.task + " " + r.error + " " + r.key).toLowerCase().indexOf(q) >= 0;
        Object.keys(selects).forEach(function (k) { if (selects[k].value && String(r[k]) !== selects[k].value) ok = false; });
        if (outcome.value === "success" && !r.success) ok = false;
        if (outcome.value === "failed" && r.success) ok = false;
        if (outcome.value === "error" && !r.error) ok = false;
        trs[i].hidden = !ok;
        if (ok) shown++;
      });
      count.textContent = shown === rows.length ? rows.length + " episodes" : shown + " of " + rows.length + " shown";
    }

    function sortBy(key) {
      sortDir = sortKey === key ? -sortDir : 1;
      sortKey = key;
      ths.forEach(function (th) {
        if (th.getAttribute("data-key") === key) th.setAttribute("aria-sort", sortDir > 0 ? "ascending" : "descending");
        else th.removeAttribute("aria-sort");
      });
      var order = rows.map(function (_, i) { return i; });
      order.sort(function (a, b) {
        var x = rows[a][key], y = rows[b][key];
        if (typeof x === "boolean") { x = x ? 1 : 0; y = y ? 1 : 0; }
        var c = typeof x === "number" && typeof y === "number" ? x - y : String(x).localeCompare(String(y));
        return c * sortDir || a - b;
      });
      var frag = document.createDocumentFragment();
      order.forEach(function (i) { frag.appendChild(trs[i]); });
      body.appendChild(frag);
    }
    apply();
  }

  buildSummary();
  buildPlots();
  buildEpisodes();
  document.getElementById("footer").textContent = "Generated by " + D.generator + " · self-contained page (no network)";
})();
