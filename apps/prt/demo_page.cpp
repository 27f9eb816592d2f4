#include "demo_page.hpp"

#include <fmt/format.h>

#include <sstream>

#include "demo_haar.hpp"
#include "prt/core/file.hpp"
#include "prt/transfer/haar_rows.hpp"
#include "prt/core/json.hpp"
#include "prt/core/version.hpp"

namespace prt::cli {

namespace {

std::string htmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// "shadowed" or "glossy (shadowed matrix, phong?...)".
std::string modeTitle(const ModeResult& m, const GlossyBake* g) {
  if (!m.glossy || !g) return toString(m.mode);
  return fmt::format("glossy: {} transfer matrices, {}", toString(m.mode), g->material.spec());
}

/// The head, the live viewer and the scene's paragraph.
void writeIntro(std::ostream& h, const DemoScene& scene, const BakeFile& bake, const DemoArgs& a,
                double bakeSeconds, double totalSeconds, const std::string& webWhy) {
  h << R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>prtkit demo</title>
<style>
body{font-family:system-ui,sans-serif;margin:2em auto;padding:0 2em;max-width:1500px;color:#222;background:#fafafa;line-height:1.4}
h1,h2,h3{font-weight:600} table{border-collapse:collapse;margin:.5em 0}
td,th{border:1px solid #ccc;padding:.25em .6em;text-align:right;font-variant-numeric:tabular-nums}
th{background:#eee} .imgs{display:grid;grid-template-columns:repeat(3,1fr);gap:.6em} figure{margin:0}
figcaption{font-size:.85em;color:#555} img{display:block;max-width:100%} .imgs img{width:100%}
code{background:#eee;padding:0 .2em} .preview{max-width:420px}
.mode{border-top:1px solid #ddd;padding-top:.5em;margin-top:1em} .note{max-width:75em}
</style></head><body>
<h1>prtkit demo</h1>
)";
  // The live viewer (prt web, docs/web.md) above the still images.
  if (webWhy.empty())
    h << "<iframe src=\"web/index.html\" title=\"live viewer\" style=\"width:100%;height:540px;"
         "border:1px solid #ccc;background:#000\"></iframe>\n<p>Live, in this browser (WebGL2): "
         "left-drag orbits, right-drag (or shift-drag) turns the light, the panel switches "
         "environments, transfer modes and bands; drop another <code>.glb</code> bake or SH light "
         "<code>.json</code> on it. <a href=\"web/index.html\">Open it full-window</a>; "
         "<code>prt web scene.glb -o DIR</code> writes the same for any bake. The same bake in "
         "an ordinary three.js scene, beside standard materials: <a "
         "href=\"web/three/index.html\">web/three/</a> (the prtkit-three module, "
         "docs/three.md).</p>\n";
  else
    h << "<p class=\"note\">(No live viewer here: " << htmlEscape(webWhy) << ")</p>\n";
  h << "<p>Scene: " << htmlEscape(scene.description) << ", " << bake.mesh.vertexCount()
    << " vertices, " << bake.mesh.triangleCount() << " triangles. Baked with " << a.bands
    << " SH bands (" << a.bands * a.bands << " coefficients), " << a.samples
    << " cosine-weighted Sobol' directions per vertex, " << a.bounces
    << " inter-reflection bounce(s), in " << fmt::format("{:.1f}", bakeSeconds)
    << " s. Reference: " << a.referenceSamples
    << " Monte Carlo samples per vertex (environment importance sampling and cosine sampling "
       "combined by MIS), no spherical harmonics anywhere. Total "
    << fmt::format("{:.0f}", totalSeconds) << " s.</p>\n";
  h << "<p class=\"note\">How to read it: every mode should match the reference up to the SH "
       "truncation (the table's <i>truncation floor</i>: the error a perfect transfer of that many "
       "bands would still have) plus noise. <b>Shadowed</b> and "
       "<b>inter-reflected</b> PRT carry only the low-frequency part of visibility × light: "
       "ambient occlusion, soft shadows and colour bleeding come out right, but a sharp sun "
       "shadow is blurred (and can ring) at "
    << a.bands
    << " bands — the error image shows where. Bake more bands (<code>--bands 9</code>) or use "
       "a softer environment to watch it shrink. Errors near the reference's own noise are below "
       "what this comparison can resolve.</p>\n";
}

/// The bake's rays and timings per mode, the glossy paragraph, and the files.
void writeBakeTable(std::ostream& h, const BakeFile& bake, const std::vector<LightResult>& lights,
                    const DemoArgs& a, const GlossyBake* glossy) {
  h << "<table><tr><th>mode</th><th>rays</th><th>time</th><th>Mrays/s</th><th>std. error of "
       "T<sub>00</sub> (mean)</th></tr>\n";
  for (const BakedTransfer& t : bake.transfers) {
    if (t.stats.rays == 0) {  // unshadowed: the clamped-cosine lobe in closed form
      h << "<tr><td>" << toString(t.mode())
        << "</td><td colspan=\"4\" style=\"text-align:left\">exact: the clamped-cosine lobe "
           "about the normal, in closed form (no rays)</td></tr>\n";
      continue;
    }
    h << fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{:.2f} s</td><td>{:.1f}</td><td>{:.2e}</td></tr>\n",
        toString(t.mode()), t.stats.rays, t.stats.secondsTotal, t.stats.raysPerSecond / 1e6,
        t.stats.stdErrT0Mean);
  }
  if (glossy) {
    const BakedTransfer& t = glossy->file.transfers.front();
    h << fmt::format(
        "<tr><td>glossy ({} matrices, {} bands, {} samples)</td><td>{}</td><td>{:.2f} s</td>"
        "<td>{:.1f}</td><td>{:.2e}</td></tr>\n",
        toString(t.mode()), t.transfer.bands(), t.recipe.samples, t.stats.rays,
        t.stats.secondsTotal, t.stats.raysPerSecond / 1e6, t.stats.stdErrT0Mean);
  }
  h << "</table>\n";
  double glossySeconds = glossy ? glossy->seconds : 0;
  for (const LightResult& L : lights)
    for (const ModeResult& m : L.modes)
      if (m.glossy) glossySeconds += m.seconds;
  if (glossy)
    h << "<p class=\"note\">Glossy (" << fmt::format("{:.0f}", glossySeconds)
      << " s of the total: the bake, then per environment its reference at "
      << a.glossyReferenceSamples
      << " samples per vertex, each a diffuse and a glossy one, and the pictures): "
         "<code>glossy.glb</code> ("
      << fmt::format("{:.0f}", glossy->bytes / 1e6) << " MB: a " << a.glossyBands * a.glossyBands
      << "×" << a.glossyBands * a.glossyBands
      << " matrix per vertex) holds inter-reflected transfer matrices M<sub>p</sub>, "
         "L'<sub>p</sub> "
         "= M<sub>p</sub>L the light arriving at p, shadowed and bounced "
      << a.bounces << " time(s) off surfaces of the material <code>"
      << htmlEscape(glossy->material.spec())
      << "</code> (glossy bounces: what a surface sends toward p depends on the direction); the "
         "material at p is applied at relighting time, each vertex seen from the stills' camera "
         "(<code>prt view glossy.glb</code> relights it live, <code>prt render glossy.glb "
         "--material ...</code> with another lobe at p). Its reference uses the same lobe, at p "
         "and at every bounce, with no SH, "
         "so the error is SH truncation of visibility, light <i>and</i> lobe (the table's last "
         "column: the lobe's energy beyond b bands) plus noise.</p>\n";
  h << "<p>Files: <code>scene.glb</code> (the bake; any glTF viewer opens it as a mesh), "
       "<code>lights/*.json</code> (SH lighting), <code>validation/*.json</code>. Try "
       "<code>prt render scene.glb --light lights/"
    << (lights.empty() ? "sky" : lights.front().name) << ".json -o mine.png</code>.</p>\n";
}

/// One environment: its preview, each mode's pictures and table, the turntable.
void writeLight(std::ostream& h, const LightResult& L, const DemoArgs& a,
                const GlossyBake* glossy) {
  h << "<h2 data-exposure=\"" << jsonFloat(L.exposure).dump() << "\">" << htmlEscape(L.spec)
    << "</h2>\n<p>Pictures at " << fmt::format("{:.2f}", L.exposure)
    << " stops (auto exposure: the model's median at light grey, at most 2% of its pixels "
       "clipped; the live viewer opens at the first environment's).</p>\n"
    << "<figure class=\"preview\"><img src=\"" << L.preview
    << "\"><figcaption>The environment (top), its " << a.bands
    << "-band SH reconstruction, and the irradiance/π it gives a white surface.</figcaption>"
       "</figure>\n";
  for (const ModeResult& m : L.modes) {
    const render::ValidationReport& r = m.report;
    h << "<div class=\"mode\"><h3>" << htmlEscape(modeTitle(m, glossy))
      << "</h3><div class=\"imgs\">";
    h << "<figure><img src=\"" << m.prtImage << "\"><figcaption>PRT, " << r.bands
      << " bands</figcaption></figure>";
    h << "<figure><img src=\"" << m.refImage
      << "\"><figcaption>Monte Carlo reference (no SH)</figcaption></figure>";
    h << "<figure><img src=\"" << m.errImage
      << fmt::format(
             "\"><figcaption>relative error per vertex: black 0 … white {:.1f}% "
             "(the reference's own noise: {:.1f}%)",
             100 * m.errorScale, 100 * r.rows.back().refStdErr)
      << "</figcaption></figure></div>\n";
    h << "<table><tr><th>bands</th><th>rel. RMSE</th><th>energy-weighted</th><th>mean rel. "
         "error</th><th>max rel. error</th><th>truncation floor</th><th>reference std. "
         "error</th>"
      << (m.glossy ? "<th>lobe energy &gt; b</th>" : "") << "</tr>\n";
    for (const render::BandRow& row : r.rows)
      h << fmt::format(
               "<tr><td>{}</td><td>{:.2f}%</td><td>{:.2f}%</td><td>{:.2f}%</td><td>{:.1f}%</td>"
               "<td>{:.2f}%</td><td>{:.2f}%</td>",
               row.bands, 100 * row.relRmse, 100 * row.energyRel, 100 * row.meanRel,
               100 * row.maxRel, 100 * row.floor, 100 * row.refStdErr)
        << (m.glossy ? fmt::format("<td>{:.1f}%</td>", 100 * row.lobeEnergyBeyond) : "")
        << "</tr>\n";
    h << "</table></div>\n";
  }
  h << "<p><a href=\"" << L.comparison
    << "\">All modes in one picture</a> (rows: unshadowed, shadowed, inter-reflected"
    << (glossy ? ", glossy" : "") << "; columns: PRT, reference, error).</p>\n";
  if (!L.frames.empty()) {
    h << "<h3>The light turning about +Y (inter-reflected, SH rotation)</h3>\n<img id=\"turn_"
      << L.name << "\" src=\"" << L.frames.front() << "\"><p><a href=\"" << L.turntable
      << "\">contact sheet</a></p>\n<script>(function(){const f=[";
    for (std::size_t k = 0; k < L.frames.size(); ++k)
      h << (k ? "," : "") << '"' << L.frames[k] << '"';
    h << "];let i=0;const im=document.getElementById(\"turn_" << L.name
      << "\");setInterval(()=>{i=(i+1)%f.length;im.src=f[i];},150);})();</script>\n";
  }
}

/// The per-texel row: the coarse box per vertex, per texel, per vertex at the same bytes, and
/// the reference, with each one's bytes and error.
void writeTexelRow(std::ostream& h, const TexelRow& t) {
  h << "<h2>Per-texel transfer: the Cornell box as a coarse mesh</h2>\n<p>Inter-reflected "
       "transfer, "
    << t.bands << " bands, under " << htmlEscape(t.environment)
    << ". A box of 2 × 2 quads a wall stores one transfer vector per vertex and smears its "
       "shadows and colour bleeding across whole walls; per texel of a "
    << t.resolution
    << "² lightmap over its packed charts (<code>prt bake --domain texels</code>) "
       "the same mesh gets them at texel resolution. Beside them, per vertex on the box "
       "tessellated to as many vertices as the lightmap has texels: the same bytes of transfer. "
       "The reference is brute-force Monte Carlo (no SH) at the "
    << t.referenceVertices << " vertices of a fine tessellation (those on a surface's edge "
       "estimated 1 mm inside it, where the light is, not on the corner line, where half the "
       "rays pass under the adjacent surface), "
    << t.referenceSamples << " samples each, in two forms: the exact relighting under the light cut to " << t.bands
    << " bands (what a noise-free bake at any resolution would give: the errors against it are "
       "the storage's) and the brute force with no SH (the band limit's error included: the "
       "sky's sun casts a sharp shadow no "
    << t.bands << "-band light can). The errors are relative RMSEs over the model's pixels; "
    << fmt::format("the reference's own noise is {:.1f}% of them.", 100 * t.referenceNoise)
    << " Per vertex at the same bytes has vertices on every corner, where a vertex's rays pass "
       "under the adjacent surface, and it draws that darkness along the corners; the lightmap's "
       "samples lie at texel centres, off the corners. An asset whose mesh is fixed has the "
       "first two choices only.</p>\n<div class=\"imgs\">";
  for (const TexelRowEntry* e : {&t.coarse, &t.texels, &t.dense})
    h << "<figure><img src=\"" << e->image << "\"><figcaption>" << htmlEscape(e->label)
      << fmt::format(": {} rows, {:.0f} KB; rel. RMSE {:.1f}% ({:.1f}% against the brute force)",
                     e->rows, e->bytes / 1024.0, 100 * e->relRmse, 100 * e->relRmseFull)
      << "</figcaption></figure>";
  h << "<figure><img src=\"" << t.referenceImage
    << fmt::format(
           "\"><figcaption>Monte Carlo reference, light cut to {} bands</figcaption>"
           "</figure>",
           t.bands)
    << "<figure><img src=\"" << t.fullReferenceImage
    << "\"><figcaption>Monte Carlo reference, no SH</figcaption></figure></div>\n";
}

/// The all-frequency row: SH and Haar at the same bytes per vertex, per environment.
void writeHaarRow(std::ostream& h, const HaarRow& r) {
  h << "<h2>All-frequency shadows: SH and Haar wavelets at the same bytes</h2>\n<p>Shadowed "
       "transfer of the same scene stored two ways in the same bytes per vertex: "
    << r.bands << " SH bands (" << r.bands * r.bands * 4
    << " B), and Haar wavelets over a " << r.resolution << "² cube map, each vertex's " << r.terms
    << " largest terms (" << haar::storedHaarRowBytes(r.resolution, r.terms)
    << " B, quantised to 16 bits; <code>prt bake --basis haar</code>, docs/haar.md, after Ng, Ramamoorthi &amp; "
       "Hanrahan 2003). The Haar rows hold the shadow only (the occluded part of the transfer); "
       "the light is the environment's "
    << r.lightTerms
    << " largest wavelet terms. Both are measured against the same brute-force Monte Carlo "
       "reference (no basis) at "
    << r.vertices << " vertices, " << r.referenceSamples << " samples each.</p>\n<table>"
    << "<tr><th>environment</th><th>SH rel. RMSE</th><th>SH energy-weighted</th><th>Haar rel. "
       "RMSE</th><th>Haar energy-weighted</th><th>reference noise</th></tr>\n";
  for (const HaarRowLight& L : r.lights)
    h << "<tr><td>" << htmlEscape(L.environment) << "</td>"
      << fmt::format("<td>{:.1f}%</td><td>{:.1f}%</td><td>{:.1f}%</td><td>{:.1f}%</td><td>{:.1f}%"
                     "</td></tr>\n",
                     100 * L.sh.relRmse, 100 * L.sh.energyRel, 100 * L.haar.relRmse,
                     100 * L.haar.energyRel, 100 * L.refStdErr);
  h << "</table>\n";
  for (const HaarRowLight& L : r.lights) {
    h << "<div class=\"imgs\">";
    for (const HaarRowEntry* e : {&L.sh, &L.haar})
      h << "<figure><img src=\"" << e->image << "\"><figcaption>" << htmlEscape(e->label) << ", "
        << htmlEscape(L.environment)
        << fmt::format(": {} B a vertex, rel. RMSE {:.1f}%", e->bytesPerVertex, 100 * e->relRmse)
        << "</figcaption></figure>";
    h << "</div>\n";
  }
}

}  // namespace

void writeDemoPage(const std::string& path, const DemoScene& scene, const BakeFile& bake,
                   const std::vector<LightResult>& lights, const DemoArgs& a, double bakeSeconds,
                   double totalSeconds, const std::string& webWhy, const GlossyBake* glossy,
                   const TexelRow* texels, const HaarRow* haar) {
  std::ostringstream h;
  writeIntro(h, scene, bake, a, bakeSeconds, totalSeconds, webWhy);
  writeBakeTable(h, bake, lights, a, glossy);
  for (const LightResult& L : lights) writeLight(h, L, a, glossy);
  if (texels) writeTexelRow(h, *texels);
  if (haar) writeHaarRow(h, *haar);
  h << "<p>Made by <code>prt demo</code> (prtkit " << kVersion
    << "). Relative error per vertex: sqrt(Σ<sub>c</sub>(R<sub>PRT</sub>−R<sub>ref</sub>)² / "
       "Σ<sub>c</sub>(R<sub>ref</sub>² + ε)); energy-weighted: ‖R<sub>PRT</sub>−R<sub>ref</sub>‖ / "
       "‖R<sub>ref</sub>‖ over all vertices; the truncation floor is the error a perfect "
       "transfer would still have at that band count: the error of exact band-limited "
       "relighting, estimated from the reference's own samples (see docs/validation.md).</p>\n"
       "</body></html>\n";
  writeFileAtomically(path, h.str());
}

}  // namespace prt::cli
