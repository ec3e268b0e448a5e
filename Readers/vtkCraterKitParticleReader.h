/**
 * @class vtkCraterKitParticleReader
 * @brief Reads particles written by other codes into the CraterKit data model.
 *
 * Formats (chosen by extension unless Format is set): LAMMPS / LIGGGHTS text dumps
 * (`.dump`, `.liggghts`, `.lammpstrj`, and the same gzip-compressed, `.gz`), pkdgrav `.ss`
 * (XDR), and CraterKit's DEM checkpoints (`.ckdem`). A dump holding several snapshots
 * advertises each as a time step (its ITEM: TIME, else its step number); ParaView's file
 * series reader turns numbered files into time steps. Parsing lives in Solvers/io/
 * (LammpsDump.h, PkdgravSs.h, FileBytes.h); bad files give an error naming the file and the
 * line or byte.
 *
 * Output: one vertex per particle with the point arrays of docs/architecture.md ("Data
 * model") that the file holds (Velocity, AngularVelocity, Radius, Mass, Density, Material =
 * LAMMPS type - 1, Id) plus every other column under its own name; field data Time, TimeStep,
 * BoxBounds.
 */
#ifndef vtkCraterKitParticleReader_h
#define vtkCraterKitParticleReader_h

#include "CraterKitReadersModule.h"
#include <vtkPolyDataAlgorithm.h>

#include <memory>
#include <string>

class CRATERKITREADERS_EXPORT vtkCraterKitParticleReader : public vtkPolyDataAlgorithm {
public:
  static vtkCraterKitParticleReader* New();
  vtkTypeMacro(vtkCraterKitParticleReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Formats { AUTOMATIC = 0, LAMMPS_DUMP = 1, PKDGRAV_SS = 2, CRATERKIT_CHECKPOINT = 3 };

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  vtkSetClampMacro(Format, int, AUTOMATIC, CRATERKIT_CHECKPOINT);
  vtkGetMacro(Format, int);
  // pkdgrav files: 1 = the file is in pkdgrav units (AU, solar mass, yr/2pi), converted to SI;
  // 0 = the file is already in SI.
  vtkSetMacro(PkdgravUnits, int);
  vtkGetMacro(PkdgravUnits, int);

  // 1 if the file's extension is one this reader handles.
  static int CanReadFile(const char* name);

protected:
  vtkCraterKitParticleReader();
  ~vtkCraterKitParticleReader() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  int Format = AUTOMATIC;
  int PkdgravUnits = 1;

private:
  vtkCraterKitParticleReader(const vtkCraterKitParticleReader&) = delete;
  void operator=(const vtkCraterKitParticleReader&) = delete;
  struct Cache;
  std::unique_ptr<Cache> Loaded;
  void Load(); // reads and indexes the file when the name or format changed; throws on errors
};

#endif
