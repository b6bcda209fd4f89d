/* step_occt.cpp — the Open CASCADE part of the STEP reader, behind the C
 * interface of step.h. Open CASCADE parses and transfers the file (after
 * our pre-scan, read_step.c), with its document layer for assemblies and
 * colours; every face, placed by its instance, is converted to NURBS with
 * BRepBuilderAPI_NurbsConvert, and its wires become parameter-space trim
 * loops from the edges' p-curves. Everything past this point (loop
 * validation, limits, trimming, drawing) is ours. The library's exceptions
 * stop here: each becomes an error ("file: message") or, for one face, a
 * skipped face with a warning. */
extern "C" {
#include "envelope.h"
#include "step.h"
}

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Message_ProgressIndicator.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeAlgo.hxx>
#include <ShapeAlgo_AlgoContainer.hxx>
#include <ShapeAlgo_ToolContainer.hxx>
#include <ShapeFix_Face.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeFix_Wire.hxx>
#include <Standard_Failure.hxx>
#include <StepData_StepModel.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <TransferBRep.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XCAFPrs.hxx>
#include <XCAFPrs_DocumentExplorer.hxx>
#include <XCAFPrs_IndexedDataMapOfShapeStyle.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>

namespace {

typedef std::chrono::steady_clock clock_type;

/* The time cap: Open CASCADE's transfer polls UserBreak. */
class deadline_progress : public Message_ProgressIndicator {
public:
    explicit deadline_progress(double seconds)
        : start_(clock_type::now()), seconds_(seconds) {}
    Standard_Boolean UserBreak() override { return elapsed() > seconds_; }
    void Show(const Message_ProgressScope &, const Standard_Boolean) override {}
    double elapsed() const
    {
        return std::chrono::duration<double>(clock_type::now() - start_).count();
    }
    double seconds() const { return seconds_; }

private:
    clock_type::time_point start_;
    double seconds_;
};

/* The shape healing a STEP transfer runs, less the repair of edges whose
 * p-curve crosses itself (ShapeFix_Wire::FixSelfIntersectingEdge): it
 * intersects each p-curve with itself through polygon interference, which
 * on a 7 KB hostile file took 6.8 s inside one face, where no deadline
 * can stop it. Loop validation checks the loops we build from the
 * p-curves anyway (docs/step.md). */
class healing_tools : public ShapeAlgo_ToolContainer {
public:
    Handle(ShapeFix_Shape) FixShape() const override
    {
        Handle(ShapeFix_Shape) fix = ShapeAlgo_ToolContainer::FixShape();
        fix->FixFaceTool()->FixWireTool()->FixSelfIntersectingEdgeMode() = 0;
        return fix;
    }
};

/* Set up once: Open CASCADE writes its messages to stdout, where the
 * command line's output is read by scripts, so its printers are removed;
 * and the transfer's healing is ours (healing_tools). */
void setup_library()
{
    static bool done = false;
    if (done)
        return;
    done = true;
    const Handle(Message_Messenger) &m = Message::DefaultMessenger();
    m->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    ShapeAlgo::Init();
    ShapeAlgo::AlgoContainer()->SetToolContainer(new healing_tools);
}

/* One face to convert: the face placed by its instance, its colour, and
 * the STEP instance it came from. */
struct placed_face {
    TopoDS_Face face;
    bool has_color;
    float rgb[3];
    int step_id;
};

/* The faces of a transferred document, leaf instances in order, each
 * moved by its instance's placement; a colour set on the face (or on a
 * shell or solid holding it) wins over the instance's. */
void collect_faces(const Handle(TDocStd_Document) &doc, std::vector<placed_face> &out)
{
    for (XCAFPrs_DocumentExplorer ex(doc, XCAFPrs_DocumentExplorerFlags_OnlyLeafNodes);
         ex.More(); ex.Next()) {
        const XCAFPrs_DocumentNode &node = ex.Current();
        TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(node.RefLabel);
        if (shape.IsNull())
            continue;
        XCAFPrs_IndexedDataMapOfShapeStyle styles;
        XCAFPrs::CollectStyleSettings(node.RefLabel, TopLoc_Location(), styles);
        /* styles are listed from the whole part down to single faces, so a
         * later (narrower) one overrides */
        std::unordered_map<const void *, Quantity_Color> face_color;
        for (int i = 1; i <= styles.Extent(); i++) {
            const XCAFPrs_Style &st = styles.FindFromIndex(i);
            if (!st.IsSetColorSurf())
                continue;
            for (TopExp_Explorer fe(styles.FindKey(i), TopAbs_FACE); fe.More(); fe.Next())
                face_color[fe.Current().TShape().get()] = st.GetColorSurf();
        }
        for (TopExp_Explorer fe(shape, TopAbs_FACE); fe.More(); fe.Next()) {
            placed_face pf;
            pf.face = TopoDS::Face(fe.Current().Moved(node.Location));
            pf.has_color = false;
            pf.step_id = 0;
            Quantity_Color c;
            auto it = face_color.find(fe.Current().TShape().get());
            if (it != face_color.end()) {
                c = it->second;
                pf.has_color = true;
            } else if (node.Style.IsSetColorSurf()) {
                c = node.Style.GetColorSurf();
                pf.has_color = true;
            }
            if (pf.has_color) {
                pf.rgb[0] = (float)c.Red();
                pf.rgb[1] = (float)c.Green();
                pf.rgb[2] = (float)c.Blue();
            }
            out.push_back(pf);
        }
    }
}

/* The STEP instance (#id) each transferred face came from, by the face's
 * shape (placements aside). */
std::unordered_map<const void *, int> face_ids(STEPControl_Reader &reader)
{
    std::unordered_map<const void *, int> ids;
    Handle(StepData_StepModel) model = Handle(StepData_StepModel)::DownCast(reader.Model());
    Handle(XSControl_WorkSession) ws = reader.WS();
    if (model.IsNull() || ws.IsNull() || ws->TransferReader().IsNull())
        return ids;
    Handle(Transfer_TransientProcess) tp = ws->TransferReader()->TransientProcess();
    if (tp.IsNull())
        return ids;
    for (int i = 1; i <= tp->NbMapped(); i++) {
        TopoDS_Shape s = TransferBRep::ShapeResult(tp->MapItem(i));
        if (s.IsNull() || s.ShapeType() != TopAbs_FACE)
            continue;
        int id = model->IdentLabel(tp->Mapped(i));
        if (id > 0)
            ids[s.TShape().get()] = id;
    }
    return ids;
}

/* Reads `text` into a new document. Fails with a message. */
bool transfer(const char *text, size_t size, const char *name, deadline_progress *progress,
              Handle(TDocStd_Document) &doc, std::unordered_map<const void *, int> *ids,
              std::string &why)
{
    STEPCAFControl_Reader reader;
    reader.SetColorMode(true);
    reader.SetNameMode(true);
    reader.SetLayerMode(false);
    reader.SetPropsMode(false);
    std::istringstream in(std::string(text, size));
    IFSelect_ReturnStatus st = reader.ChangeReader().ReadStream(name, in);
    if (st != IFSelect_RetDone) {
        why = "Open CASCADE could not read the file's data";
        return false;
    }
    doc = new TDocStd_Document("XmlXCAF");
    XCAFDoc_DocumentTool::Set(doc->Main(), false);
    /* a file with no shapes at all is an empty scene, not an error */
    if (reader.ChangeReader().NbRootsForTransfer() == 0)
        return true;
    bool ok = reader.Transfer(doc, progress->Start());
    if (progress->UserBreak()) {
        char buf[96];
        snprintf(buf, sizeof buf, "reading took more than %.0f s (the limit; docs/limits.md)",
                 progress->seconds());
        why = buf;
        return false;
    }
    if (!ok) {
        why = "Open CASCADE could not transfer the file's shapes";
        return false;
    }
    if (ids)
        *ids = face_ids(reader.ChangeReader());
    return true;
}

/* ---- conversion of one face into the scene model ---- */

void copy_knots(const TColStd_Array1OfReal &k, const TColStd_Array1OfInteger &m, double *out)
{
    int n = 0;
    for (int i = k.Lower(); i <= k.Upper(); i++)
        for (int r = 0; r < m(i); r++)
            out[n++] = k(i);
}

size_t flat_knot_count(const TColStd_Array1OfInteger &m)
{
    size_t n = 0;
    for (int i = m.Lower(); i <= m.Upper(); i++)
        n += (size_t)m(i);
    return n;
}

/* Whether a knot vector's end knots have multiplicity degree + 1. */
bool clamped(const TColStd_Array1OfInteger &m, int degree)
{
    return m(m.Lower()) == degree + 1 && m(m.Upper()) == degree + 1;
}

/* The face's p-curve of one edge as a clamped 2-D B-spline, in the
 * direction the wire runs. */
bool edge_curve(const TopoDS_Edge &e, const TopoDS_Face &f, sc_curve *out, std::string &why)
{
    double first, last;
    Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, f, first, last);
    if (pc.IsNull()) {
        why = "an edge has no parameter-space curve";
        return false;
    }
    if (!(last > first)) {
        why = "an edge has an empty parameter range";
        return false;
    }
    Handle(Geom2d_BSplineCurve) bc =
        Geom2dConvert::CurveToBSplineCurve(new Geom2d_TrimmedCurve(pc, first, last));
    if (bc.IsNull()) {
        why = "an edge's curve could not be converted to a B-spline";
        return false;
    }
    if (bc->IsPeriodic() || !clamped(bc->Multiplicities(), bc->Degree())) {
        /* the scene model's knot vectors are clamped */
        bc = Handle(Geom2d_BSplineCurve)::DownCast(bc->Copy());
        if (bc->IsPeriodic())
            bc->SetNotPeriodic();
        if (!clamped(bc->Multiplicities(), bc->Degree()))
            bc->Segment(bc->FirstParameter(), bc->LastParameter());
    }
    if (e.Orientation() == TopAbs_REVERSED)
        bc->Reverse();
    int deg = bc->Degree(), n = bc->NbPoles();
    if (deg < 1 || deg > SC_READ_MAX_DEGREE) {
        why = "an edge's curve has a degree above " + std::to_string(SC_READ_MAX_DEGREE);
        return false;
    }
    if (flat_knot_count(bc->Multiplicities()) != (size_t)(n + deg + 1)) {
        why = "an edge's curve has an unexpected knot vector";
        return false;
    }
    sc_curve_alloc(out, 2, deg, n);
    copy_knots(bc->Knots(), bc->Multiplicities(), out->knots);
    for (int i = 0; i < n; i++) {
        gp_Pnt2d p = bc->Pole(i + 1);
        double w = bc->Weight(i + 1);
        out->cp[3 * i + 0] = p.X() * w;
        out->cp[3 * i + 1] = p.Y() * w;
        out->cp[3 * i + 2] = w;
    }
    return true;
}

void free_curves(std::vector<sc_curve> &cs)
{
    for (sc_curve &c : cs)
        sc_curve_free(&c);
    cs.clear();
}

/* End point (end = 1) or start point of a 2-D curve, as (u, v). */
void curve_end(const sc_curve *c, int end, double p[2])
{
    const double *q = c->cp + 3 * (end ? c->ncp - 1 : 0);
    p[0] = q[0] / q[2];
    p[1] = q[1] / q[2];
}

void move_end(sc_curve *c, int end, const double p[2])
{
    double *q = c->cp + 3 * (end ? c->ncp - 1 : 0);
    q[0] = p[0] * q[2];
    q[1] = p[1] * q[2];
}

/* Consecutive p-curves of a wire meet within the library's edge
 * tolerances, not exactly: gaps up to SNAP of the domain's size are
 * closed here by moving both ends to their middle (clamped curves end at
 * their end control points), so that loop validation warns only about
 * real gaps. */
const double SNAP = 1e-7;

void close_small_gaps(std::vector<sc_curve> &cs, double size)
{
    for (size_t k = 0; k < cs.size(); k++) {
        sc_curve *a = &cs[k], *b = &cs[(k + 1) % cs.size()];
        double pa[2], pb[2];
        curve_end(a, 1, pa);
        curve_end(b, 0, pb);
        double gap = std::hypot(pa[0] - pb[0], pa[1] - pb[1]);
        if (gap > 0 && gap <= SNAP * size) {
            double mid[2] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])};
            move_end(a, 1, mid);
            move_end(b, 0, mid);
        }
    }
}

/* The trim loops of face `f` (already converted) into `s`: each wire one
 * loop, the outer wire not a hole. A wire whose curves cannot be had is
 * left out with its reason in `why`; then the face is skipped. */
bool face_loops(const TopoDS_Face &f, sc_surface *s, sc_budget *budget, const char *name,
                int line, sc_error *err, std::string &why, bool *over_budget)
{
    TopoDS_Wire outer = BRepTools::OuterWire(f);
    std::vector<sc_loop> loops;
    for (TopExp_Explorer we(f, TopAbs_WIRE); we.More(); we.Next()) {
        TopoDS_Wire w = TopoDS::Wire(we.Current());
        std::vector<sc_curve> curves;
        for (BRepTools_WireExplorer ee(w, f); ee.More(); ee.Next()) {
            sc_curve c;
            memset(&c, 0, sizeof c);
            if (!edge_curve(ee.Current(), f, &c, why)) {
                free_curves(curves);
                break;
            }
            curves.push_back(c);
            if ((int)curves.size() > SC_MAX_LOOP_PIECES) {
                why = "a wire has more edges than a loop may have";
                free_curves(curves);
                break;
            }
            if (sc_budget_charge(budget, sc_curve_bytes(2, c.degree, c.ncp), "trim curve", name,
                                 line, err)) {
                *over_budget = true;
                free_curves(curves);
                break;
            }
        }
        if (curves.empty()) {
            for (sc_loop &l : loops) {
                for (int k = 0; k < l.ncurves; k++)
                    sc_curve_free(&l.curves[k]);
                free(l.curves);
            }
            if (why.empty())
                why = "a wire has no edges";
            return false;
        }
        double u0 = s->knots_u[s->deg_u], u1 = s->knots_u[s->nu];
        double v0 = s->knots_v[s->deg_v], v1 = s->knots_v[s->nv];
        close_small_gaps(curves, std::max(u1 - u0, v1 - v0));
        sc_loop l;
        l.is_hole = w.IsSame(outer) ? 0 : 1;
        l.ncurves = (int)curves.size();
        l.curves = (sc_curve *)sc_alloc(curves.size(), sizeof(sc_curve));
        memcpy(l.curves, curves.data(), curves.size() * sizeof(sc_curve));
        /* The outer loop first: some consumers look at it first. */
        if (l.is_hole)
            loops.push_back(l);
        else
            loops.insert(loops.begin(), l);
    }
    s->nloops = (int)loops.size();
    s->loops = loops.empty() ? NULL : (sc_loop *)sc_alloc(loops.size(), sizeof(sc_loop));
    if (!loops.empty())
        memcpy(s->loops, loops.data(), loops.size() * sizeof(sc_loop));
    return true;
}

/* Face `pf` as one surface of `scene`; false with the reason in `why`
 * when the face is skipped, or with `err` set when the geometry budget is
 * spent (the whole read fails then). */
bool convert_face(const placed_face &pf, int index, sc_scene *scene, sc_budget *budget,
                  const char *name, int line, sc_error *err, std::string &why,
                  bool *over_budget)
{
    /* A face already on a B-spline surface keeps it and its p-curves: the
     * conversion would change nothing, but on a surface with a pole it
     * re-projects every p-curve (ProjLib_ComputeApproxOnPolarSurface), up
     * to seconds per face. */
    TopoDS_Face f = pf.face;
    TopLoc_Location loc;
    Handle(Geom_Surface) gs = BRep_Tool::Surface(f, loc);
    if (Handle(Geom_BSplineSurface)::DownCast(gs).IsNull()) {
        BRepBuilderAPI_NurbsConvert nc(pf.face, Standard_True);
        if (!nc.IsDone()) {
            why = "conversion to NURBS failed";
            return false;
        }
        f = TopoDS::Face(nc.Shape());
        gs = BRep_Tool::Surface(f, loc);
    }
    Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(gs);
    if (bs.IsNull() && !gs.IsNull()) {
        double u0, u1, v0, v1;
        BRepTools::UVBounds(f, u0, u1, v0, v1);
        bs = GeomConvert::SurfaceToBSplineSurface(
            new Geom_RectangularTrimmedSurface(gs, u0, u1, v0, v1));
    }
    if (bs.IsNull()) {
        why = "the surface has no NURBS form";
        return false;
    }
    if (bs->IsUPeriodic() || bs->IsVPeriodic() || !clamped(bs->UMultiplicities(), bs->UDegree()) ||
        !clamped(bs->VMultiplicities(), bs->VDegree())) {
        /* the scene model's knot vectors are clamped: periodic and
         * unclamped surfaces are cut to their domain */
        bs = Handle(Geom_BSplineSurface)::DownCast(bs->Copy());
        if (bs->IsUPeriodic())
            bs->SetUNotPeriodic();
        if (bs->IsVPeriodic())
            bs->SetVNotPeriodic();
        if (!clamped(bs->UMultiplicities(), bs->UDegree()) ||
            !clamped(bs->VMultiplicities(), bs->VDegree())) {
            double u0, u1, v0, v1;
            bs->Bounds(u0, u1, v0, v1);
            bs->Segment(u0, u1, v0, v1);
        }
    }
    int du = bs->UDegree(), dv = bs->VDegree(), nu = bs->NbUPoles(), nv = bs->NbVPoles();
    if (du > SC_READ_MAX_DEGREE || dv > SC_READ_MAX_DEGREE) {
        why = "degree above " + std::to_string(SC_READ_MAX_DEGREE);
        return false;
    }
    if (flat_knot_count(bs->UMultiplicities()) != (size_t)(nu + du + 1) ||
        flat_knot_count(bs->VMultiplicities()) != (size_t)(nv + dv + 1)) {
        why = "unexpected knot vectors";
        return false;
    }
    if (sc_budget_charge(budget, sc_surface_bytes(du, dv, nu, nv), "surface", name, line,
                         err)) {
        *over_budget = true;
        return false;
    }
    sc_surface *s = sc_scene_add_surface(scene);
    sc_surface_alloc(s, du, dv, nu, nv);
    copy_knots(bs->UKnots(), bs->UMultiplicities(), s->knots_u);
    copy_knots(bs->VKnots(), bs->VMultiplicities(), s->knots_v);
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            gp_Pnt p = bs->Pole(i + 1, j + 1);
            double w = bs->Weight(i + 1, j + 1);
            double *c = s->cp + 4 * ((size_t)j * nu + i);
            c[0] = p.X() * w;
            c[1] = p.Y() * w;
            c[2] = p.Z() * w;
            c[3] = w;
        }
    const gp_Trsf &t = loc.Transformation();
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 4; k++)
            s->xform[4 * r + k] = t.Value(r + 1, k + 1);
    if (pf.step_id > 0)
        snprintf(s->name, sizeof s->name, "face #%d", pf.step_id);
    else
        snprintf(s->name, sizeof s->name, "face %d", index);
    if (pf.has_color)
        memcpy(s->color, pf.rgb, sizeof s->color);
    sc_surface_update_rational(s);
    sc_error check;
    bool ok = sc_surface_check(s, &check) == SC_OK;
    if (!ok)
        why = check.message;
    else
        ok = face_loops(f, s, budget, name, line, err, why, over_budget);
    if (!ok) {
        sc_surface_free(s);
        scene->nsurfaces--;
    }
    return ok;
}

/* The reason of a face skipped, as one word for `info`'s skipped line. */
const char *skip_word(const std::string &why)
{
    if (why.find("p-curve") != std::string::npos || why.find("parameter-space") !=
        std::string::npos)
        return "no-pcurve";
    if (why.find("degree above") != std::string::npos)
        return "degree-too-high";
    if (why.find("NURBS") != std::string::npos)
        return "no-nurbs-form";
    return "conversion-failed";
}

} // namespace

extern "C" int sc_occt_read_step(const char *text, size_t size, const char *name,
                                 const sc_step_scan *scan, double max_seconds, sc_scene *scene,
                                 sc_error *err)
{
    setup_library();
    Handle(deadline_progress) progress = new deadline_progress(max_seconds);
    sc_budget budget = {0, 0};
    int face_index = 0;
    try {
        Handle(TDocStd_Document) doc;
        std::unordered_map<const void *, int> ids;
        std::string why;
        if (!transfer(text, size, name, progress.get(), doc, &ids, why))
            return sc_fail(err, name, 0, "%s", why.c_str());
        std::vector<placed_face> faces;
        collect_faces(doc, faces);
        for (placed_face &pf : faces) {
            if (progress->UserBreak())
                return sc_fail(err, name, 0, "reading took more than %.0f s (the limit; "
                               "docs/limits.md)", max_seconds);
            auto it = ids.find(pf.face.TShape().get());
            pf.step_id = it == ids.end() ? 0 : it->second;
            int line = pf.step_id ? sc_step_line_of(scan, pf.step_id) : 0;
            bool over_budget = false;
            why.clear();
            bool ok;
            face_index++;
            try {
                ok = convert_face(pf, face_index, scene, &budget, name, line, err, why,
                                  &over_budget);
            } catch (const Standard_Failure &e) {
                ok = false;
                why = std::string("Open CASCADE: ") + e.GetMessageString();
            }
            if (over_budget)
                return SC_FAIL;
            if (!ok) {
                char where[32] = "";
                if (line > 0)
                    snprintf(where, sizeof where, "%d:", line);
                sc_log(SC_LOG_WARN, "%s:%s face %s%d skipped: %s", name, where,
                       pf.step_id ? "#" : "", pf.step_id ? pf.step_id : face_index, why.c_str());
                sc_scene_skip(scene, "step-face", skip_word(why), 1);
            }
        }
        return SC_OK;
    } catch (const Standard_Failure &e) {
        return sc_fail(err, name, 0, "Open CASCADE: %s", e.GetMessageString());
    } catch (const std::exception &e) {
        return sc_fail(err, name, 0, "%s", e.what());
    } catch (...) {
        return sc_fail(err, name, 0, "Open CASCADE failed on this file");
    }
}

/* ---- the independent check: Open CASCADE's own figures ---- */

namespace {

void face_props(const TopoDS_Face &f, sc_occt_face *out)
{
    memset(out, 0, sizeof *out);
    GProp_GProps props;
    BRepGProp::SurfaceProperties(f, props, 1e-6);
    out->area = props.Mass();
    gp_Pnt c = props.CentreOfMass();
    out->centroid[0] = c.X();
    out->centroid[1] = c.Y();
    out->centroid[2] = c.Z();
    Handle(Geom_Surface) s = BRep_Tool::Surface(f);
    Handle(Geom_RectangularTrimmedSurface) rt = Handle(Geom_RectangularTrimmedSurface)::DownCast(s);
    if (!rt.IsNull())
        s = rt->BasisSurface();
    Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(s);
    if (!b.IsNull()) {
        out->bspline = 1;
        out->deg_u = b->UDegree();
        out->deg_v = b->VDegree();
    }
}

bool ends_with(const char *s, const char *ext)
{
    size_t n = strlen(s), e = strlen(ext);
    return n > e && !strcasecmp(s + n - e, ext);
}

} // namespace

extern "C" int sc_occt_face_props(const char *path, sc_occt_face **faces, int *nfaces,
                                  sc_error *err)
{
    setup_library();
    *faces = NULL;
    *nfaces = 0;
    try {
        std::vector<TopoDS_Face> list;
        if (ends_with(path, ".igs") || ends_with(path, ".iges")) {
            IGESControl_Reader reader;
            if (reader.ReadFile(path) != IFSelect_RetDone)
                return sc_fail(err, path, 0, "Open CASCADE could not read the file");
            reader.TransferRoots();
            TopoDS_Shape shape = reader.OneShape();
            for (TopExp_Explorer fe(shape, TopAbs_FACE); fe.More(); fe.Next())
                list.push_back(TopoDS::Face(fe.Current()));
        } else {
            char *text;
            size_t size;
            FILE *fp = fopen(path, "rb");
            if (!fp)
                return sc_fail(err, path, 0, "cannot open");
            std::string data;
            char buf[1 << 16];
            size_t got;
            while ((got = fread(buf, 1, sizeof buf, fp)) > 0)
                data.append(buf, got);
            fclose(fp);
            text = &data[0];
            size = data.size();
            Handle(deadline_progress) progress = new deadline_progress(SC_STEP_MAX_SECONDS);
            Handle(TDocStd_Document) doc;
            std::string why;
            if (!transfer(text, size, path, progress.get(), doc, NULL, why))
                return sc_fail(err, path, 0, "%s", why.c_str());
            std::vector<placed_face> pfs;
            collect_faces(doc, pfs);
            for (const placed_face &pf : pfs)
                list.push_back(pf.face);
        }
        *faces = (sc_occt_face *)calloc(list.size() ? list.size() : 1, sizeof **faces);
        if (!*faces)
            return sc_fail(err, path, 0, "out of memory");
        for (size_t i = 0; i < list.size(); i++)
            face_props(list[i], &(*faces)[i]);
        *nfaces = (int)list.size();
        return SC_OK;
    } catch (const Standard_Failure &e) {
        free(*faces);
        *faces = NULL;
        return sc_fail(err, path, 0, "Open CASCADE: %s", e.GetMessageString());
    }
}
