// Layout check of the report page, injected into a scratch copy by h4cal_report_test.sh
// (the report itself has no script). On load it looks for what a reader would see as
// broken at this window width, and writes its findings into a pre element, id layout-check:
// "layout ok" when there are none, one line per finding otherwise.
//   (a) nothing wider than the window: the page scrolls sideways, or a figure, table or
//       heading reaches past its right edge (clipped);
//   (b) no two sibling blocks (sections, figures, tables, headings, paragraphs) overlap;
//   (c) every SVG figure has a size.
window.addEventListener("load", () => {
  const findings = [];
  const width = window.innerWidth;
  const name = (e) => e.tagName.toLowerCase() + (e.id ? "#" + e.id : "") +
      (e.closest("section") ? " in section " + e.closest("section").id : "");

  if (document.documentElement.scrollWidth > width) {
    findings.push(`page ${document.documentElement.scrollWidth} px wide in a ${width} px window`);
  }
  for (const e of document.querySelectorAll("figure, svg, table, h1, h2, h3, nav, p, pre")) {
    const r = e.getBoundingClientRect();
    if (r.left < -0.5 || r.right > width + 0.5) {
      findings.push(`${name(e)} spans ${r.left.toFixed(0)}..${r.right.toFixed(0)} px, past the ` +
                    `${width} px window`);
    }
  }

  const blocks = "section, figure, table, h1, h2, h3, nav, p, ul, ol, pre, div";
  for (const parent of document.querySelectorAll("body, section, nav, figure, div")) {
    const children = Array.from(parent.children).filter((c) => c.matches(blocks))
        .map((c) => [c, c.getBoundingClientRect()])
        .filter(([, r]) => r.width > 0 && r.height > 0);
    for (let i = 0; i < children.length; ++i) {
      for (let j = i + 1; j < children.length; ++j) {
        const [a, ra] = children[i], [b, rb] = children[j];
        const dx = Math.min(ra.right, rb.right) - Math.max(ra.left, rb.left);
        const dy = Math.min(ra.bottom, rb.bottom) - Math.max(ra.top, rb.top);
        if (dx > 1 && dy > 1) findings.push(`${name(a)} and ${name(b)} overlap`);
      }
    }
  }

  for (const svg of document.querySelectorAll("svg")) {
    const r = svg.getBoundingClientRect();
    if (!(r.width > 0 && r.height > 0)) findings.push(`${name(svg)} has no size`);
  }

  const out = document.createElement("pre");
  out.id = "layout-check";
  out.dataset.height = String(document.documentElement.scrollHeight);
  out.textContent = findings.length ? findings.join("\n") : "layout ok";
  document.body.appendChild(out);
});
