MeshVersionFormatted 2
Dimension 2
SolAtVertices
1
1 1
1e999
End
