FiniteElementSpace
FiniteElementCollection: NURBS2
VDim: 1
Ordering: 0

4
1
1
7
2
-1
-1
5
4
7
2
5
