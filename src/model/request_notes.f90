module superjoin_model_request_notes
  !! The one listing note on the output variables that file requests
  !! (*NODE FILE, *EL FILE and their *NODE OUTPUT / *ELEMENT OUTPUT aliases)
  !! name but superjoin does not produce (CalculiX's NOE, SMID, PEEQ, ...).
  !! Print requests say it in their own REQUESTED OUTPUT tables.
  use superjoin_model_types, only: model_t, REQ_NODE_FILE, REQ_EL_FILE, REQ_KIND_NAMES
  implicit none (type, external)
  private

  public :: unproduced_file_variables

contains

  function unproduced_file_variables(model) result(text)
    !! 'output variables not produced ...: NOE, SMID (*EL FILE)' naming each
    !! variable once per request kind, or '' when the file requests name none.
    type(model_t), intent(in) :: model
    character(:), allocatable :: text
    character(:), allocatable :: part
    integer :: kind
    text = ''
    if (.not. allocated(model%requests)) return
    do kind = REQ_NODE_FILE, REQ_EL_FILE
       part = kind_variables(model, kind)
       if (len(part) == 0) cycle
       if (len(text) > 0) text = text//'; '
       text = text//part//' ('//trim(REQ_KIND_NAMES(kind))//')'
    end do
    if (len(text) > 0) text = 'output variables not produced by superjoin (linear statics): '//text
  end function unproduced_file_variables

  function kind_variables(model, kind) result(list)
    !! The distinct not-produced variables of the requests of one kind, in deck order.
    type(model_t), intent(in) :: model
    integer, intent(in) :: kind
    character(:), allocatable :: list
    integer :: k, i
    list = ''
    do k = 1, size(model%requests)
       if (model%requests(k)%kind /= kind .or. .not. allocated(model%requests(k)%ignored)) cycle
       do i = 1, size(model%requests(k)%ignored)
          associate (v => model%requests(k)%ignored(i)%s)
            if (index(' '//list//',', ' '//v//',') > 0) cycle
            if (len(list) > 0) list = list//', '
            list = list//v
          end associate
       end do
    end do
  end function kind_variables
end module superjoin_model_request_notes
