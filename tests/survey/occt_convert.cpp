// occt_convert — writes an Open CASCADE shape (.brep, or the .rle of Draw,
// a .brep behind a one-line header) as the STEP and IGES files of the real-file
// survey (docs/step.md, docs/iges.md, `make survey`), so that the readers meet
// the forms other CAD systems write: STEP AP203 and AP214 as the shape is
// (solids stay solids), AP214 as a shell-based surface model (faces), IGES as
// faces (144 on 108/120/128) and as a B-rep (186/510 on 190–198/128).
// A tool of the survey, not part of the library: built by `make survey` only
// when Open CASCADE is installed.
// Usage: occt_convert SHAPE OUTDIR   (writes OUTDIR/NAME-{ap203,ap214,ap214-shells}.stp
//        and OUTDIR/NAME-{faces,brep}.igs; prints one line per file written)
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Gravity.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS_Shape.hxx>

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

static bool read_shape(const std::string &path, TopoDS_Shape &shape)
{
    std::ifstream in(path);
    if (!in) return false;
    std::stringstream all;
    all << in.rdbuf();
    std::string text = all.str();
    // Draw's .rle files put "DBRep_DrawableShape" before the BRep text.
    size_t at = text.find("CASCADE Topology");
    if (at == std::string::npos) return false;
    std::istringstream brep(text.substr(at));
    BRep_Builder builder;
    BRepTools::Read(shape, brep, builder);
    return !shape.IsNull();
}

static int write_step(const TopoDS_Shape &shape, const std::string &out, const char *schema,
                      STEPControl_StepModelType mode)
{
    Interface_Static::SetCVal("write.step.schema", schema);
    STEPControl_Writer w;
    if (w.Transfer(shape, mode) != IFSelect_RetDone) return 0;
    return w.Write(out.c_str()) == IFSelect_RetDone;
}

static int write_iges(const TopoDS_Shape &shape, const std::string &out, int brep)
{
    IGESControl_Writer w("MM", brep);
    if (!w.AddShape(shape)) return 0;
    w.ComputeModel();
    return w.Write(out.c_str()) ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        std::cerr << "usage: occt_convert SHAPE OUTDIR\n";
        return 2;
    }
    // Open CASCADE prints its progress on stdout; the survey reads stdout.
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    std::string in = argv[1], dir = argv[2];
    std::string name = in.substr(in.find_last_of('/') + 1);
    for (auto &c : name) if (c == '.') c = '_';
    TopoDS_Shape shape;
    try {
        if (!read_shape(in, shape)) {
            std::cerr << in << ": not an Open CASCADE shape\n";
            return 1;
        }
    } catch (const Standard_Failure &e) {
        std::cerr << in << ": " << e.GetMessageString() << "\n";
        return 1;
    }
    IGESControl_Controller::Init();
    struct { const char *suffix; int kind; } outs[] = {
        {"-ap203.stp", 0}, {"-ap214.stp", 1}, {"-ap214-shells.stp", 2},
        {"-faces.igs", 3}, {"-brep.igs", 4},
    };
    int failed = 0;
    for (auto &o : outs) {
        std::string out = dir + "/" + name + o.suffix;
        int ok = 0;
        try {
            switch (o.kind) {
            case 0: ok = write_step(shape, out, "AP203", STEPControl_AsIs); break;
            case 1: ok = write_step(shape, out, "AP214IS", STEPControl_AsIs); break;
            case 2: ok = write_step(shape, out, "AP214IS", STEPControl_ShellBasedSurfaceModel); break;
            case 3: ok = write_iges(shape, out, 0); break;
            case 4: ok = write_iges(shape, out, 1); break;
            }
        } catch (const Standard_Failure &e) {
            std::cerr << out << ": " << e.GetMessageString() << "\n";
        }
        if (ok) std::cout << out << "\n";
        else { std::cerr << out << ": not written\n"; failed++; }
    }
    return failed ? 1 : 0;
}
