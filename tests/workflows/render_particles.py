"""Renders the particle XDMF of a DEM checkpoint with ParaView (pvpython, headless) into a PNG.

The scene (docs/formats/particle-xdmf.md): every particle as a translucent sphere of its
diameter, every contact as a tube from centre to centre coloured by its normal force (the force
chains), and the periodic cell as an outline, seen from an oblique camera. A file without
contacts renders its particles alone.

usage: pvpython render_particles.py FILE.xmf OUTPUT.png
"""
import sys

from paraview import simple

if len(sys.argv) != 3:
    sys.exit(__doc__)
source, output = sys.argv[1:]


def grid(name):
    """One grid of the file: XDMFReader reads the grids it is given as blocks of one dataset."""
    reader = simple.XDMFReader(FileNames=[source], GridStatus=[name])
    reader.UpdatePipeline()
    return reader


probe = simple.XDMFReader(FileNames=[source])
probe.UpdatePipelineInformation()
grids = list(probe.GridStatus.Available)
if "particles" not in grids:
    sys.exit(f"render_particles.py: no 'particles' grid in {source} (grids: {grids})")

particles = grid("particles")
n_particles = particles.GetDataInformation().GetNumberOfPoints()
low, high = particles.PointData["diameter"].GetRange()
if n_particles == 0 or not high > 0:
    sys.exit(f"render_particles.py: {source}: {n_particles} particles, diameters up to {high}")
# The Sphere glyph has radius 0.5, so a scale factor of 1 on the diameter gives the true size.
spheres = simple.Glyph(Input=particles, GlyphType="Sphere")
spheres.ScaleArray = ["POINTS", "diameter"]
spheres.ScaleFactor = 1.0
spheres.GlyphMode = "All Points"
spheres.GlyphType.ThetaResolution = 16
spheres.GlyphType.PhiResolution = 12

view = simple.GetActiveViewOrCreate("RenderView")
view.ViewSize = [640, 480]
if hasattr(view, "UseColorPaletteForBackground"):  # ParaView 5.10 and later: else the palette wins
    view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
view.OrientationAxesVisibility = 0

shown = simple.Show(spheres, view)
simple.ColorBy(shown, None)
shown.AmbientColor = shown.DiffuseColor = [0.72, 0.72, 0.78]
shown.Opacity = 0.3  # translucent, so that the chains inside the assembly show

message = f"render_particles.py: {source}: {n_particles} particles, diameter in [{low:.4g}, {high:.4g}] m"
if "contacts" in grids:
    contacts = grid("contacts")
    n_contacts = contacts.GetDataInformation().GetNumberOfCells()
    f_low, f_high = contacts.CellData["normal_force"].GetRange()
    # The Tube filter takes polygonal data: the reader gives an unstructured grid.
    tubes = simple.Tube(Input=simple.ExtractSurface(Input=contacts))
    tubes.Radius = 0.08 * low
    tubes.NumberofSides = 8
    chains = simple.Show(tubes, view)
    simple.ColorBy(chains, ("CELLS", "normal_force"))
    chains.LookupTable = simple.GetColorTransferFunction("normal_force")
    chains.LookupTable.ApplyPreset("Inferno (matplotlib)", True)
    chains.LookupTable.RescaleTransferFunction(0.0, f_high)
    chains.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(chains.LookupTable, view)
    bar.Title, bar.ComponentTitle = "normal force [N]", ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]  # the default white vanishes on white
    message += f", {n_contacts} contacts, normal force in [{f_low:.4g}, {f_high:.4g}] N"
else:
    message += ", no contacts"

if "cell" in grids:
    box = simple.Show(grid("cell"), view)
    box.SetRepresentationType("Outline")
    simple.ColorBy(box, None)
    box.AmbientColor = box.DiffuseColor = [0.0, 0.0, 0.0]
    box.LineWidth = 2.0

print(message)
view.CameraPosition = [1.0, -1.5, 1.2]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera()
simple.SaveScreenshot(output, view, ImageResolution=[640, 480])
