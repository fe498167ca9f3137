"""Renders an aniso XDMF file with ParaView (pvpython, headless) into a PNG.

The scene: the first cell array as a threshold surface (for a voxel image, the
solid phase), coloured by that array, seen from an oblique camera.

usage: pvpython render_xdmf.py FILE.xmf OUTPUT.png
"""
import sys

from paraview import simple

if len(sys.argv) != 3:
    sys.exit(__doc__)
source, output = sys.argv[1:]
reader = simple.XDMFReader(FileNames=[source])
reader.UpdatePipeline()
arrays = reader.CellData.keys()
if not arrays:
    sys.exit(f"render_xdmf.py: ParaView read no cell arrays from {source}")
name = arrays[0]
low, high = reader.CellData[name].GetRange()
print(f"render_xdmf.py: {source}: cell array '{name}' in [{low}, {high}], "
      f"{reader.GetDataInformation().GetNumberOfCells()} cells")
shown = simple.Threshold(Input=reader, Scalars=["CELLS", name])
shown.LowerThreshold, shown.UpperThreshold = high, high  # the top phase: the solid of a voxel image
view = simple.GetActiveViewOrCreate("RenderView")
view.ViewSize = [640, 480]
if hasattr(view, "UseColorPaletteForBackground"):  # ParaView 5.10 and later: else the palette wins
    view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
display = simple.Show(shown, view)
simple.ColorBy(display, ("CELLS", name))
view.CameraPosition = [1.0, -1.5, 1.2]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera()
simple.SaveScreenshot(output, view, ImageResolution=[640, 480])
