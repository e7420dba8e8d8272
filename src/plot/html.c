/* One self-contained HTML page of a plot document: plotly.js inlined (no network), each
 * panel a plotly figure, tables as HTML tables, 3-D mode shapes animated, and the
 * numbers behind each section downloadable as CSV (a Blob made by the page). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

void pl_json_text(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c == '\n')
            fputs("\\n", f);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else if (c == '<' && s[1] == '/') /* no "</script>" inside the page's script */
            fputs("<\\/", f), s++;
        else
            fputc(c, f);
    }
    fputc('"', f);
}

void pl_json_number(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.12g", v);
    else
        fputs("null", f);
}

static void array(FILE *f, const double *v, int n)
{
    fputc('[', f);
    for (int i = 0; i < n; i++) {
        if (i) fputc(',', f);
        pl_json_number(f, v[i]);
    }
    fputc(']', f);
}

static const char *symbol_name(pl_symbol s)
{
    return s == PL_SQUARE     ? "square"
           : s == PL_DIAMOND  ? "diamond"
           : s == PL_TRIANGLE ? "triangle-up"
                              : "circle";
}

static void trace_json(FILE *f, const pl_trace *t)
{
    fputs("{\"type\":\"scatter\",\"name\":", f);
    pl_json_text(f, t->name);
    if (t->y2) fputs(",\"yaxis\":\"y2\"", f);
    fputs(",\"x\":", f);
    array(f, t->x, t->n);
    fputs(",\"y\":", f);
    array(f, t->y, t->n);
    static const char *const modes[] = {"lines", "markers", "lines+markers", "lines"};
    fprintf(f, ",\"mode\":\"%s%s\",\"showlegend\":%s", modes[t->mode],
            t->label[0] && !t->text ? "+text" : "", t->legend ? "true" : "false");
    if (t->label[0] && !t->text && t->n > 0) { /* written at the last point */
        fputs(",\"text\":[", f);
        for (int i = 0; i < t->n; i++) {
            if (i) fputc(',', f);
            pl_json_text(f, i == t->n - 1 ? t->label : "");
        }
        fprintf(f, "],\"textposition\":\"%s\",\"textfont\":{\"color\":\"%s\",\"size\":11}",
                t->label_right   ? "bottom right"
                : t->label_below ? "bottom left"
                                 : "top left",
                t->color);
    }
    if (t->mode == PL_FILL)
        fprintf(f,
                ",\"fill\":\"toself\",\"fillcolor\":\"%s\",\"opacity\":0.25,\"line\":{\"width\":0,"
                "\"color\":\"%s\"}",
                t->color, t->color);
    else
        fprintf(f, ",\"line\":{\"color\":\"%s\",\"width\":1.8,\"dash\":\"%s\"}", t->color,
                t->dash ? "dash" : "solid");
    if (t->marker_color) {
        fputs(",\"marker\":{\"color\":[", f);
        for (int i = 0; i < t->n; i++)
            fprintf(f, "%s\"%s\"", i ? "," : "", t->marker_color[i]);
        fprintf(f, "],\"size\":8,\"symbol\":\"%s\"}", symbol_name(t->symbol));
    } else {
        fprintf(f, ",\"marker\":{\"color\":\"%s\",\"size\":8,\"symbol\":\"%s\"}", t->color,
                symbol_name(t->symbol));
    }
    if (t->text) {
        fputs(",\"text\":[", f);
        for (int i = 0; i < t->n; i++) {
            if (i) fputc(',', f);
            pl_json_text(f, t->text[i] ? t->text[i] : "");
        }
        fputs("],\"hovertemplate\":\"%{text}<extra></extra>\"", f);
    }
    fputc('}', f);
}

/* Tick labels: plain numbers on a linear axis whose values are neither tiny nor huge
 * (plotly's exponent forms give "0.2e+4" for 2000), powers of ten otherwise. */
static void axis_json(FILE *f, const char *label, int logscale, double lo, double hi)
{
    fputs("{\"title\":{\"text\":", f);
    pl_json_text(f, label);
    double big = fmax(fabs(lo), fabs(hi));
    int plain = !logscale && big < 1e6 && big >= 1e-3;
    fprintf(f, "},\"type\":\"%s\",\"exponentformat\":\"%s\",\"automargin\":true",
            logscale ? "log" : "linear", plain ? "none" : "power");
}

static int has_y2(const pl_panel *pn)
{
    for (int t = 0; t < pn->ntraces; t++)
        if (pn->traces[t].y2) return 1;
    return 0;
}

static void xy_json(FILE *f, const pl_panel *pn, const char *id)
{
    fputs("{\"id\":", f);
    pl_json_text(f, id);
    fputs(",\"data\":[", f);
    for (int t = 0; t < pn->ntraces; t++) {
        if (t) fputc(',', f);
        trace_json(f, &pn->traces[t]);
    }
    /* the title at the left, the toolbar upright at the right: they never overlap */
    fputs("],\"layout\":{\"title\":{\"x\":0,\"xanchor\":\"left\",\"xref\":\"paper\","
          "\"font\":{\"size\":15},\"text\":",
          f);
    if (pn->subtitle[0]) {
        size_t n = strlen(pn->title) + strlen(pn->subtitle) + 32;
        char *t = malloc(n);
        if (t) snprintf(t, n, "%s<br><sub>%s</sub>", pn->title, pn->subtitle);
        pl_json_text(f, t ? t : pn->title);
        free(t);
    } else {
        pl_json_text(f, pn->title);
    }
    double lo, hi;
    pl_range(pn, 0, &lo, &hi);
    fputs("},\"xaxis\":", f);
    axis_json(f, pn->xlabel, pn->xlog, lo, hi);
    if (pn->xint) fputs(",\"tick0\":0,\"dtick\":1", f);
    if (pn->xlim[0] < pn->xlim[1]) fprintf(f, ",\"range\":[%.10g,%.10g]", pn->xlim[0], pn->xlim[1]);
    pl_range(pn, 1, &lo, &hi);
    fputs("},\"yaxis\":", f);
    axis_json(f, pn->ylabel, pn->ylog, lo, hi);
    if (pn->ylim[0] < pn->ylim[1]) fprintf(f, ",\"range\":[%.6g,%.6g]", pn->ylim[0], pn->ylim[1]);
    if (pn->equal) fputs(",\"scaleanchor\":\"x\",\"scaleratio\":1", f);
    int two = has_y2(pn);
    if (two) {
        pl_range(pn, 2, &lo, &hi);
        fputs("},\"yaxis2\":", f);
        axis_json(f, pn->y2label, 0, lo, hi);
        fputs(",\"overlaying\":\"y\",\"side\":\"right\",\"showgrid\":false", f);
        if (pn->y2lim[0] < pn->y2lim[1])
            fprintf(f, ",\"range\":[%.6g,%.6g]", pn->y2lim[0], pn->y2lim[1]);
    }
    int nleg = 0;
    for (int t = 0; t < pn->ntraces; t++)
        nleg += pn->traces[t].legend;
    int height = pn->equal ? 520 : 440;
    if (90 + 19 * nleg > height) height = 90 + 19 * nleg; /* the whole legend, no scrolling */
    fprintf(f,
            "},\"height\":%d,\"margin\":{\"t\":%d},\"hovermode\":\"closest\","
            "\"legend\":{\"x\":%s},\"modebar\":{\"orientation\":\"v\"}}}",
            height, pn->subtitle[0] ? 80 : 60, two ? "1.1" : "1.04");
}

static void mode3d_json(FILE *f, const pl_panel *pn, const char *id)
{
    fputs("{\"id\":", f);
    pl_json_text(f, id);
    fputs(",\"title\":", f);
    pl_json_text(f, pn->title);
    fputs(",\"frames\":[", f);
    for (int k = 0; k < pn->nframes; k++) {
        if (k) fputc(',', f);
        pl_json_text(f, pn->frames[k] ? pn->frames[k] : "");
    }
    fputs("],\"traces\":[", f);
    for (int t = 0; t < pn->ntraces; t++) {
        const pl_trace *c = &pn->traces[t];
        if (t) fputc(',', f);
        fputs("{\"name\":", f);
        pl_json_text(f, c->name);
        fprintf(f, ",\"frame\":%d,\"color\":\"%s\",\"z\":", c->frame, c->color);
        array(f, c->x, c->n);
        fputs(",\"xr\":", f);
        array(f, c->xr, c->n);
        fputs(",\"xi\":", f);
        array(f, c->xi, c->n);
        fputs(",\"yr\":", f);
        array(f, c->yr, c->n);
        fputs(",\"yi\":", f);
        array(f, c->yi, c->n);
        fputc('}', f);
    }
    fputs("]}", f);
}

/* traces of the first mode of a 3-D panel (each drawn with its axis at rest and its
 * stations' orbits) */
static int frame0(const pl_panel *pn)
{
    int n = 0;
    for (int t = 0; t < pn->ntraces; t++)
        n += pn->traces[t].frame == 0;
    return n;
}

static void table_html(FILE *f, const pl_panel *pn)
{
    fputs("<h3>", f);
    pl_xml_text(f, pn->title);
    fputs("</h3>\n<table>\n", f);
    for (int r = 0; r <= pn->nrows; r++) {
        fputs("<tr>", f);
        for (int c = 0; c < pn->ncols; c++) {
            const char *s = pn->cells[(size_t)r * pn->ncols + c];
            fputs(r ? "<td>" : "<th>", f);
            pl_xml_text(f, s ? s : "");
            fputs(r ? "</td>" : "</th>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("</table>\n", f);
}

/* The page's own script: draws the figures, animates the 3-D mode shapes (the real part
 * of u e^{i phi} for phi over a cycle, x and y motion of each shaft station, with the
 * orbit ellipse of each station drawn along the shaft, ROSS style) and turns
 * the CSV texts into downloads. */
static const char PAGE_JS[] =
    "(function(){\n"
    "var cfg={responsive:true,displaylogo:false};\n"
    "FIGS.forEach(function(f){Plotly.newPlot(f.id,f.data,f.layout,cfg);});\n"
    "M3D.forEach(function(m){\n"
    " var div=document.getElementById(m.id),sel=document.getElementById(m.id+'-sel');\n"
    " var phi=0,cur=[];\n"
    " function pick(k){cur=m.traces.filter(function(t){return t.frame===k;});\n"
    "  var a=1e-300;cur.forEach(function(t){for(var i=0;i<t.z.length;i++){\n"
    "   a=Math.max(a,Math.hypot(t.xr[i],t.xi[i]),Math.hypot(t.yr[i],t.yi[i]));}});\n"
    "  cur.scale=1/a;\n"
    /* each station's orbit: the ellipse the point traces over a cycle (37 points, a
     * null between stations), fixed while the deflected line turns along it */
    "  cur.forEach(function(t){var ox=[],oy=[],oz=[];for(var i=0;i<t.z.length;i++){\n"
    "   for(var j=0;j<=36;j++){var c=Math.cos(Math.PI*j/18),s=Math.sin(Math.PI*j/18);\n"
    "    ox.push(t.z[i]);oy.push(cur.scale*(t.xr[i]*c-t.xi[i]*s));\n"
    "    oz.push(cur.scale*(t.yr[i]*c-t.yi[i]*s));}ox.push(null);oy.push(null);oz.push(null);}\n"
    "   t.orb={x:ox,y:oy,z:oz};});}\n"
    " function data(){var d=[];cur.forEach(function(t){var y=[],z=[];\n"
    "  var c=Math.cos(phi),s=Math.sin(phi);for(var i=0;i<t.z.length;i++){\n"
    "   y.push(cur.scale*(t.xr[i]*c-t.xi[i]*s));z.push(cur.scale*(t.yr[i]*c-t.yi[i]*s));}\n"
    "  d.push({type:'scatter3d',mode:'lines+markers',name:t.name,x:t.z,y:y,z:z,\n"
    "   line:{color:t.color,width:6},marker:{size:3,color:t.color}});\n"
    "  d.push({type:'scatter3d',mode:'lines',name:t.name+' (at rest)',x:t.z,\n"
    "   y:t.z.map(function(){return 0;}),z:t.z.map(function(){return 0;}),showlegend:false,\n"
    "   line:{color:'#999',width:2,dash:'dash'}});\n"
    "  d.push({type:'scatter3d',mode:'lines',name:t.name+' orbits',x:t.orb.x,y:t.orb.y,\n"
    "   z:t.orb.z,showlegend:false,hoverinfo:'skip',opacity:0.55,\n"
    "   line:{color:t.color,width:2}});});return d;}\n"
    " var lay={title:{text:m.title},height:560,margin:{t:50},scene:{xaxis:{title:{text:'axial "
    "position (m)'}},\n"
    "  yaxis:{title:{text:'x (scaled)'},range:[-1.1,1.1]},zaxis:{title:{text:'y "
    "(scaled)'},range:[-1.1,1.1]},\n"
    "  aspectmode:'manual',aspectratio:{x:2.5,y:1,z:1}}};\n"
    " m.frames.forEach(function(l,k){var "
    "o=document.createElement('option');o.value=k;o.text=l;sel.add(o);});\n"
    " pick(0);Plotly.newPlot(div,data(),lay,cfg);\n"
    " sel.onchange=function(){pick(+sel.value);Plotly.react(div,data(),lay,cfg);};\n"
    " var run=document.getElementById(m.id+'-run');\n"
    " if(window.matchMedia&&matchMedia('(prefers-reduced-motion: "
    "reduce)').matches)run.checked=false;\n"
    " var n=0;setInterval(function(){if(!run.checked)return;\n"
    "  n=(n+1)%24;phi=2*Math.PI*n/24;Plotly.react(div,data(),lay,cfg);},120);\n"
    "});\n"
    "document.querySelectorAll('a.csv').forEach(function(a){\n"
    " a.href=URL.createObjectURL(new Blob([CSV[+a.dataset.csv]],{type:'text/csv'}));});\n"
    "})();\n";

static const char PAGE_CSS[] =
    "body{font-family:sans-serif;margin:24px;max-width:1200px;color:#222}"
    "h1{font-size:22px}h2{font-size:19px;border-bottom:1px solid #ccc;margin-top:36px}"
    "h3{font-size:15px}table{border-collapse:collapse;font-size:12px;margin-bottom:12px}"
    "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}th{background:#f2f2f2}"
    "nav a{margin-right:14px}a.csv{font-size:13px}.note{font-size:13px;color:#444}"
    ".plot{margin:6px 0}";

/* bytes of the library, a '\0' marking the '/' of a "</script" */
static void emit(FILE *f, const char *b, size_t n)
{
    const char *z;
    while (n && (z = memchr(b, '\0', n))) {
        fwrite(b, 1, (size_t)(z - b), f);
        fputs("\\/", f);
        n -= (size_t)(z - b) + 1;
        b = z + 1;
    }
    fwrite(b, 1, n, f);
}

static gd_status inline_plotly(FILE *f, const char *path, gd_error *err)
{
    FILE *in = fopen(path, "rb");
    if (!in)
        return gd_error_set(err, GD_EIO, path, 0, 0, "", "run 'make deps' or set GEARDYN_PLOTLY_JS",
                            "cannot read plotly.js");
    /* a "</script" inside the library would end the element early */
    char buf[65536 + 16];
    size_t keep = 0, n;
    while ((n = fread(buf + keep, 1, 65536, in)) > 0) {
        n += keep;
        keep = n < 8 ? n : 8; /* strlen("</script") */
        for (size_t i = 0; i + 8 <= n; i++)
            if (!memcmp(buf + i, "</script", 8)) buf[i + 1] = '\0';
        emit(f, buf, n - keep);
        memmove(buf, buf + n - keep, keep);
    }
    emit(f, buf, keep);
    int bad = ferror(in);
    fclose(in);
    if (bad) return gd_error_set(err, GD_EIO, path, 0, 0, "", "", "read error");
    return GD_OK;
}

gd_status pl_write_html(const gd_plot *p, FILE *f, const char *plotly_path, gd_error *err)
{
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
          "<meta name=\"generator\" content=\"geardyn\">\n<title>",
          f);
    pl_xml_text(f, p->title);
    fprintf(f, "</title>\n<style>%s</style>\n<script>\n", PAGE_CSS);
    gd_status st = inline_plotly(f, plotly_path, err);
    if (st) return st;
    fputs("\n</script>\n</head><body>\n<h1>", f);
    pl_xml_text(f, p->title);
    fputs("</h1>\n", f);
    if (p->nsections > 1) {
        fputs("<nav>", f);
        for (int i = 0; i < p->nsections; i++) {
            fprintf(f, "<a href=\"#s%d\">", i);
            pl_xml_text(f, p->sections[i].title);
            fputs("</a>", f);
        }
        fputs("</nav>\n", f);
    }
    char id[48];
    for (int i = 0; i < p->nsections; i++) {
        const pl_section *s = &p->sections[i];
        fprintf(f, "<section id=\"s%d\"><h2>", i);
        pl_xml_text(f, s->title);
        fputs("</h2>\n", f);
        if (s->note) {
            fputs("<p class=\"note\">", f);
            pl_xml_text(f, s->note);
            fputs("</p>\n", f);
        }
        if (s->csv_len) {
            fprintf(f, "<p><a class=\"csv\" data-csv=\"%d\" download=\"", i);
            pl_xml_text(f, s->csv_name[0] ? s->csv_name : "data.csv");
            fputs("\">Download the numbers of this section (CSV)</a></p>\n", f);
        }
        for (int k = 0; k < s->npanels; k++) {
            const pl_panel *pn = &s->panels[k];
            snprintf(id, sizeof id, "p%d-%d", i, k);
            if (pn->kind == PL_XY)
                fprintf(f, "<div class=\"plot\" id=\"%s\" data-traces=\"%d\"></div>\n", id,
                        pn->ntraces);
            else if (pn->kind == PL_MODE3D)
                fprintf(f,
                        "<p>mode <select id=\"%s-sel\"></select> <label><input type=\"checkbox\" "
                        "id=\"%s-run\" checked> animate</label></p>\n<div class=\"plot mode3d\" "
                        "id=\"%s\" data-traces=\"%d\"></div>\n",
                        id, id, id, 3 * frame0(pn));
            else
                table_html(f, pn);
        }
        fputs("</section>\n", f);
    }
    fputs("<script>\nvar FIGS=[", f);
    int first = 1;
    for (int i = 0; i < p->nsections; i++)
        for (int k = 0; k < p->sections[i].npanels; k++) {
            if (p->sections[i].panels[k].kind != PL_XY) continue;
            snprintf(id, sizeof id, "p%d-%d", i, k);
            if (!first) fputs(",\n", f);
            first = 0;
            xy_json(f, &p->sections[i].panels[k], id);
        }
    fputs("];\nvar M3D=[", f);
    first = 1;
    for (int i = 0; i < p->nsections; i++)
        for (int k = 0; k < p->sections[i].npanels; k++) {
            if (p->sections[i].panels[k].kind != PL_MODE3D) continue;
            snprintf(id, sizeof id, "p%d-%d", i, k);
            if (!first) fputs(",\n", f);
            first = 0;
            mode3d_json(f, &p->sections[i].panels[k], id);
        }
    fputs("];\nvar CSV=[", f);
    for (int i = 0; i < p->nsections; i++) {
        if (i) fputs(",\n", f);
        pl_json_text(f, p->sections[i].csv ? p->sections[i].csv : "");
    }
    fprintf(f, "];\n%s</script>\n</body></html>\n", PAGE_JS);
    if (ferror(f)) return gd_error_set(err, GD_EIO, "", 0, 0, "", "", "write error");
    return GD_OK;
}
