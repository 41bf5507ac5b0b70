/**
 * @class   vtkIGASyntheticDeformation
 * @brief   Turns a static volume of rational Bézier hexahedra into a deforming time series:
 *          twist, bend, travelling wave or a free-form deformation (FFD) lattice bulge.
 *
 * The output advertises NumberOfTimeSteps time steps evenly over [0, 1] (TIME_STEPS and
 * TIME_RANGE) and deforms by the requested UPDATE_TIME_STEP (clamped to [0, 1]), or by `Time`
 * when no time is requested; time 0 is the input. The deformation is sized to the input's point
 * bounds and applied to the control points (iga::boxDeformation and iga::deformControlPoints in
 * Kernels/include/iga/Deformation.h): the output cells are the splines with the moved control
 * points, weights and attributes unchanged. That is what a solver or an FFD animation of the
 * control net produces, and for the FFD lattice it is a choice: the lattice is applied to the
 * control points, not composed with the volume (that would multiply the degrees).
 *
 * With GenerateDisplacement on, the output also carries the applied displacement of every
 * control point as the active vectors "Displacement" (so vtkIGADisplaceControlPoints with scale
 * -1 restores the input) and its length as the attribute "DisplacementMagnitude", an attribute
 * that varies over time (interpolated like any attribute between control points).
 */
#ifndef vtkIGASyntheticDeformation_h
#define vtkIGASyntheticDeformation_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class IGAVIEWFILTERS_EXPORT vtkIGASyntheticDeformation : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkIGASyntheticDeformation* New();
  vtkTypeMacro(vtkIGASyntheticDeformation, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    TWIST = 0,
    BEND = 1,
    WAVE = 2,
    LATTICE = 3
  };

  ///@{
  /// The deformation (default TWIST).
  vtkSetClampMacro(Mode, int, TWIST, LATTICE);
  vtkGetMacro(Mode, int);
  void SetModeToTwist() { this->SetMode(TWIST); }
  void SetModeToBend() { this->SetMode(BEND); }
  void SetModeToWave() { this->SetMode(WAVE); }
  void SetModeToLattice() { this->SetMode(LATTICE); }
  ///@}

  ///@{
  /// Axis of the deformation, 0 = x, 1 = y, 2 = z (default). Bend and wave displace along the
  /// next axis ((Axis + 1) % 3).
  vtkSetClampMacro(Axis, int, 0, 2);
  vtkGetMacro(Axis, int);
  ///@}

  ///@{
  /// Size at time 1, relative to the input's bounds (L: their extent along the axis): twist:
  /// radians over L; bend: tip displacement / L; wave: amplitude / L; lattice: the middle
  /// layer's scaling about the axis minus 1. Default 1.
  vtkSetMacro(Amount, double);
  vtkGetMacro(Amount, double);
  ///@}

  ///@{
  /// Wave only: wavelength / L (default 0.5).
  vtkSetMacro(Wavelength, double);
  vtkGetMacro(Wavelength, double);
  ///@}

  ///@{
  /// Number of advertised time steps over [0, 1] (default 11, at least 2).
  vtkSetClampMacro(NumberOfTimeSteps, int, 2, VTK_INT_MAX);
  vtkGetMacro(NumberOfTimeSteps, int);
  ///@}

  ///@{
  /// Time in [0, 1] used when the pipeline requests none (default 1).
  vtkSetClampMacro(Time, double, 0.0, 1.0);
  vtkGetMacro(Time, double);
  ///@}

  ///@{
  /// Add the "Displacement" vectors and the "DisplacementMagnitude" attribute (default off).
  vtkSetMacro(GenerateDisplacement, bool);
  vtkGetMacro(GenerateDisplacement, bool);
  vtkBooleanMacro(GenerateDisplacement, bool);
  ///@}

protected:
  vtkIGASyntheticDeformation();
  ~vtkIGASyntheticDeformation() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Mode = TWIST;
  int Axis = 2;
  double Amount = 1.0;
  double Wavelength = 0.5;
  int NumberOfTimeSteps = 11;
  double Time = 1.0;
  bool GenerateDisplacement = false;

private:
  vtkIGASyntheticDeformation(const vtkIGASyntheticDeformation&) = delete;
  void operator=(const vtkIGASyntheticDeformation&) = delete;
};

#endif
